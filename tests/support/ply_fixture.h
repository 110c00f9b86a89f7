// The smallest binary PLY mesh, one triangle (0,0,0), (1,0,0), (0,1,0), for the tests and
// fuzzers that need a mesh file in a scene bundle. Header-only: the fuzzers build without the
// test support library.
#pragma once

#include <cstdint>
#include <string>

namespace pf::testing {

inline std::string TrianglePly() {
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
        "y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ply.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
    const unsigned char count = 3;
    const int32_t face[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(&count), 1);
    ply.append(reinterpret_cast<const char*>(face), sizeof face);
    return ply;
}

}  // namespace pf::testing
