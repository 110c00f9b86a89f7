// SHA-256 through OpenSSL, for content addresses of scene bundles and blobs.
#pragma once

#include <string>
#include <string_view>

namespace pf {

// Incremental: Update with any number of pieces, then HexDigest once.
class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void Update(std::string_view bytes);
    std::string HexDigest();  // 64 lowercase hex characters

private:
    struct State;
    State* state_;
};

std::string Sha256Hex(std::string_view bytes);

}  // namespace pf
