// libFuzzer target for EXT_meshopt_compression: the input's first four bytes choose the
// stream's mode and filter, its stride and its count, the rest is the stream; decoded to
// exactly count x stride bytes or refused, never a crash, a sanitizer report or a leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene_io/gltf/gltf_meshopt.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 4) return 0;
    static const char* kModes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
    static const char* kFilters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
    pf::MeshoptStream stream;
    stream.mode = kModes[data[0] % 3];
    stream.filter = kFilters[(data[0] / 3) % 4];
    stream.stride = data[1];
    stream.count = data[2] | (uint64_t{data[3]} << 8);
    const std::string_view compressed(reinterpret_cast<const char*>(data + 4), size - 4);
    const absl::StatusOr<std::string> decoded = pf::DecodeMeshoptStream(compressed, stream);
    if (decoded.ok() && decoded->size() != stream.count * stream.stride) __builtin_trap();
    return 0;
}
