// Test credentials from deploy/make-certs.sh.
#include "tests/support/farm_credentials.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/support/child_process.h"
#include "tests/support/test_env.h"

namespace pf::testing {

std::string FarmCredentials::Read(const std::string& name) const {
    std::ifstream file(Path(name));
    std::ostringstream content;
    content << file.rdbuf();
    return content.str();
}

std::vector<std::string> FarmCredentials::CoordinatorFlags() const {
    return {"--tls-cert",          Path("coordinator.pem"),
            "--tls-key",           Path("coordinator.key"),
            "--worker-ca",         Path("ca.pem"),
            "--client-token-file", Path("client-tokens"),
            "--worker-token-file", Path("worker-tokens")};
}

std::vector<std::string> FarmCredentials::WorkerFlags() const {
    return {"--tls-ca",  Path("ca.pem"),     "--tls-cert",   Path("worker.pem"),
            "--tls-key", Path("worker.key"), "--token-file", Path("worker-token")};
}

std::vector<std::string> FarmCredentials::ClientFlags() const {
    return {"--tls-ca", Path("ca.pem"), "--token-file", Path("client-token")};
}

ChannelSecurity FarmCredentials::Client() const {
    ChannelSecurity security;
    security.ca_pem = Read("ca.pem");
    security.token = ClientToken();
    return security;
}

ChannelSecurity FarmCredentials::Worker() const {
    ChannelSecurity security = Client();
    security.cert_pem = Read("worker.pem");
    security.key_pem = Read("worker.key");
    security.token = WorkerToken();
    return security;
}

const FarmCredentials& TestCredentials(const std::string& source_dir) {
    // In this process's own folder (removed with it at exit), so that no other test's files
    // are ever read, nor a stale set left by an earlier process of the same pid.
    static const FarmCredentials credentials = [&] {
        FarmCredentials made;
        made.dir = FreshTempDir("credentials").string();
        ChildProcess script({"/bin/bash", source_dir + "/deploy/make-certs.sh", made.dir});
        while (script.ReadLine(60)) {
        }
        EXPECT_EQ(script.Wait(60), 0) << "deploy/make-certs.sh failed";
        return made;
    }();
    return credentials;
}

}  // namespace pf::testing
