// The dashboard's HTTP(S) transport and its event streams.
#include "server/dashboard_server.h"

#include <httplib.h>
#include <openssl/pem.h>
#include <openssl/ssl.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>

#include <algorithm>
#include <cctype>
#include <chrono>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "server/job_views.h"
#include "wire/json.h"

namespace pf {
namespace {

// A stream checks for a change, a closed connection and shutdown this often, and sends a
// comment when it has been quiet for kKeepAlive (proxies close silent connections).
constexpr auto kStreamPoll = std::chrono::milliseconds(250);
constexpr auto kKeepAlive = std::chrono::seconds(15);
constexpr auto kListInterval = std::chrono::seconds(1);  // the job and worker lists' cadence
constexpr size_t kThreads = DashboardServer::kMaxStreams + 16;

HttpRequest FromHttplib(const httplib::Request& request) {
    HttpRequest out{request.method, request.path, {}, {}, request.body, request.remote_addr};
    for (const auto& [name, value] : request.params) out.query.emplace(name, value);
    for (const auto& [name, value] : request.headers) {
        std::string lower = name;
        std::transform(lower.begin(), lower.end(), lower.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        out.headers.emplace(std::move(lower), value);
    }
    return out;
}

void Reply(const HttpResponse& response, httplib::Response& out) {
    out.status = response.status;
    for (const auto& [name, value] : response.headers) out.set_header(name, value);
    out.set_header("X-Content-Type-Options", "nosniff");
    out.set_header("X-Frame-Options", "DENY");
    // Only the coordinator's own script, style and images; no framing.
    out.set_header("Content-Security-Policy", "default-src 'self'; frame-ancestors 'none'");
    out.set_content(response.body, response.content_type);
}

// The certificate chain and key from PEM text into the TLS context.
bool LoadCertificate(SSL_CTX& context, const std::string& cert_pem, const std::string& key_pem) {
    SSL_CTX_set_min_proto_version(&context, TLS1_2_VERSION);
    std::unique_ptr<BIO, decltype(&BIO_free)> certs(
        BIO_new_mem_buf(cert_pem.data(), static_cast<int>(cert_pem.size())), BIO_free);
    X509* leaf = PEM_read_bio_X509(certs.get(), nullptr, nullptr, nullptr);
    if (leaf == nullptr || SSL_CTX_use_certificate(&context, leaf) != 1) {
        X509_free(leaf);
        return false;
    }
    X509_free(leaf);
    while (X509* chain = PEM_read_bio_X509(certs.get(), nullptr, nullptr, nullptr))
        if (SSL_CTX_add_extra_chain_cert(&context, chain) != 1) {  // takes ownership on success
            X509_free(chain);
            return false;
        }
    std::unique_ptr<BIO, decltype(&BIO_free)> key(
        BIO_new_mem_buf(key_pem.data(), static_cast<int>(key_pem.size())), BIO_free);
    EVP_PKEY* private_key = PEM_read_bio_PrivateKey(key.get(), nullptr, nullptr, nullptr);
    const bool loaded = private_key != nullptr &&
                        SSL_CTX_use_PrivateKey(&context, private_key) == 1 &&
                        SSL_CTX_check_private_key(&context) == 1;
    EVP_PKEY_free(private_key);
    return loaded;
}

std::string Event(absl::string_view name, absl::string_view data) {
    return absl::StrCat("event: ", name, "\ndata: ", data, "\n\n");
}

}  // namespace

absl::StatusOr<std::unique_ptr<DashboardServer>> DashboardServer::Start(
    const std::string& address, const ServerSecurity& security, Coordinator& coordinator,
    const AccessControl& access) {
    const size_t colon = address.rfind(':');
    int port = -1;
    if (colon == std::string::npos || !absl::SimpleAtoi(address.substr(colon + 1), &port) ||
        port < 0 || port > 65535)
        return absl::InvalidArgumentError(
            absl::StrCat("--web-listen: '", address, "' is not HOST:PORT"));
    std::string host = address.substr(0, colon);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']')
        host = host.substr(1, host.size() - 2);
    std::unique_ptr<DashboardServer> server(new DashboardServer(coordinator, access));
    if (security.plaintext) {
        server->http_ = std::make_unique<httplib::Server>();
    } else {
        auto https = std::make_unique<httplib::SSLServer>([&security](SSL_CTX& context) {
            return LoadCertificate(context, security.cert_pem, security.key_pem);
        });
        if (!https->is_valid())
            return absl::InvalidArgumentError(
                "--tls-cert, --tls-key: the dashboard cannot use this certificate and key");
        server->http_ = std::move(https);
    }
    server->http_->new_task_queue = [] { return new httplib::ThreadPool(kThreads); };
    server->http_->set_payload_max_length(1 << 16);
    // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, which would let a second
    // server bind a port in use and take half its connections.
    server->http_->set_socket_options([](int socket) {
        const int yes = 1;
        setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    server->Route();
    server->port_ = port == 0 ? server->http_->bind_to_any_port(host)
                              : (server->http_->bind_to_port(host, port) ? port : -1);
    if (server->port_ <= 0)
        return absl::UnavailableError(absl::StrCat("--web-listen: cannot listen on ", address,
                                                   " (in use, or not an address "
                                                   "of this machine)"));
    const bool bracket = host.find(':') != std::string::npos;
    server->url_ = absl::StrCat(security.plaintext ? "http" : "https", "://", bracket ? "[" : "",
                                host, bracket ? "]" : "", ":", server->port_, "/");
    server->thread_ = std::thread([http = server->http_.get()] { http->listen_after_bind(); });
    // Serving before it returns: a stop() before the listening loop starts would go unseen
    // and the loop would never end.
    while (!server->http_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return server;
}

DashboardServer::DashboardServer(Coordinator& coordinator, const AccessControl& access)
    : api_(coordinator, access) {}

DashboardServer::~DashboardServer() {
    stopping_ = true;
    if (http_) http_->stop();
    if (thread_.joinable()) thread_.join();
}

void DashboardServer::Route() {
    const auto handle = [this](const httplib::Request& request, httplib::Response& response) {
        Reply(api_.Handle(FromHttplib(request)), response);
    };
    // Opens an event stream whose next message `next` writes; refusals answer as the API does.
    const auto stream = [this](httplib::Response& response,
                               std::function<bool(httplib::DataSink&)> next) {
        if (streams_.fetch_add(1) >= kMaxStreams) {
            --streams_;
            Reply(DashboardApi::Error(absl::ResourceExhaustedError(absl::StrCat(
                      "the dashboard has ", kMaxStreams, " event streams open; try later"))),
                  response);
            return;
        }
        response.set_header("Cache-Control", "no-store");
        response.set_chunked_content_provider(
            "text/event-stream",
            [this, next = std::move(next)](size_t, httplib::DataSink& sink) {
                if (stopping_) return false;
                return next(sink);
            },
            [this](bool) { --streams_; });
    };

    // A job's stream: its status and new convergence points whenever an epoch merges.
    http_->Get(R"(/api/jobs/([^/]+)/events)", [this, stream](const httplib::Request& request,
                                                             httplib::Response& response) {
        const HttpRequest converted = FromHttplib(request);
        if (absl::Status allowed = api_.Authenticate(converted).status(); !allowed.ok())
            return Reply(DashboardApi::Error(allowed), response);
        absl::StatusOr<std::shared_ptr<Job>> job = api_.coordinator().FindJob(request.matches[1]);
        if (!job.ok()) return Reply(DashboardApi::Error(job.status()), response);
        struct State {
            std::shared_ptr<Job> job;
            uint64_t version = 0;
            size_t points_sent = 0;
            bool first = true;
        };
        auto state = std::make_shared<State>(State{std::move(*job)});
        stream(response, [this, state](httplib::DataSink& sink) {
            const Clock::time_point quiet_until = Clock::now() + kKeepAlive;
            while (!state->first) {
                if (stopping_ || !sink.is_writable()) return false;
                const uint64_t now_version =
                    state->job->WaitForChange(state->version, Clock::now() + kStreamPoll);
                if (now_version != state->version) break;
                if (Clock::now() >= quiet_until) return sink.write(": keep-alive\n\n", 14);
            }
            state->first = false;
            state->version = state->job->Version();
            const std::string event = Event("job", api_.JobEvent(*state->job, &state->points_sent));
            if (!sink.write(event.data(), event.size())) return false;
            if (!state->job->Running()) sink.done();
            return true;
        });
    });
    // The lists' stream: every job and every worker, each second.
    http_->Get("/api/events", [this, stream](const httplib::Request& request,
                                             httplib::Response& response) {
        if (absl::Status allowed = api_.Authenticate(FromHttplib(request)).status(); !allowed.ok())
            return Reply(DashboardApi::Error(allowed), response);
        auto first = std::make_shared<bool>(true);
        stream(response, [this, first](httplib::DataSink& sink) {
            for (auto waited = Clock::duration::zero(); !*first && waited < kListInterval;
                 waited += kStreamPoll) {
                if (stopping_ || !sink.is_writable()) return false;
                std::this_thread::sleep_for(kStreamPoll);
            }
            *first = false;
            const std::string events = Event("jobs", ToJson(JobListView(api_.coordinator()))) +
                                       Event("workers", ToJson(WorkerListView(api_.coordinator())));
            return sink.write(events.data(), events.size());
        });
    });
    http_->Get(".*", handle);
    http_->Post(".*", handle);
    http_->set_exception_handler(
        [](const httplib::Request& request, httplib::Response& response, std::exception_ptr) {
            spdlog::error("dashboard: {} {} failed", request.method, request.path);
            Reply(DashboardApi::Error(absl::InternalError("the request failed")), response);
        });
}

}  // namespace pf
