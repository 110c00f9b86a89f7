// TLS certificates and tokens for farm tests: a CA, the coordinator's certificate (for
// 127.0.0.1 and localhost), a worker certificate and one token per role, made once per test
// process by deploy/make-certs.sh into the process's temporary folder (test_env.h), with the
// flags that use them.
#pragma once

#include <string>
#include <vector>

#include "wire/secure_channel.h"

namespace pf::testing {

struct FarmCredentials {
    std::string dir;  // ca.pem, coordinator.pem/.key, worker.pem/.key, {client,worker}-token(s)

    std::string Path(const std::string& name) const { return dir + "/" + name; }
    std::string Read(const std::string& name) const;  // a file's content
    std::string ClientToken() const { return Read("client-token").substr(0, 64); }
    std::string WorkerToken() const { return Read("worker-token").substr(0, 64); }

    // Flags for photonfarm-coordinator (TLS, workers with certificates, both token files),
    // photonfarm-worker and the photonfarm client.
    std::vector<std::string> CoordinatorFlags() const;
    std::vector<std::string> WorkerFlags() const;
    std::vector<std::string> ClientFlags() const;
    // The same as channel settings, for clients and workers inside a test.
    ChannelSecurity Client() const;
    ChannelSecurity Worker() const;
};

// Made on first use; `source_dir` holds deploy/make-certs.sh.
const FarmCredentials& TestCredentials(const std::string& source_dir);

}  // namespace pf::testing
