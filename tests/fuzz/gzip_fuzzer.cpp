// libFuzzer target for the gzip decoder scenes' .pbrt.gz and .ply.gz go through: any bytes
// must come back decompressed or as an error, within the size limit, never a crash, a
// sanitizer report or a leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene_io/decompress.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const absl::StatusOr<std::string> out =
        pf::Gunzip(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.gz", 1 << 20);
    if (out.ok() && out->size() > (1 << 20)) __builtin_trap();  // the limit holds
    return 0;
}
