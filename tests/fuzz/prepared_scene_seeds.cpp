// Writes the prepared_scene fuzzer's seed corpus: the payload (what follows the header) of
// each scene given, so that the fuzzer starts from real scenes. Run by run_fuzzers.sh.
// Usage: prepared_scene_seeds OUT_DIR SCENE...
#include <cstdio>
#include <fstream>
#include <string>

#include "core/scene/prepared_scene.h"
#include "core/scene_io/scene_loader.h"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: prepared_scene_seeds OUT_DIR SCENE...\n");
        return 2;
    }
    for (int i = 2; i < argc; ++i) {
        const absl::StatusOr<pf::Scene> scene = pf::LoadScene(argv[i]);
        if (!scene.ok()) {
            std::fprintf(stderr, "prepared_scene_seeds: %s\n", scene.status().ToString().c_str());
            return 1;
        }
        const std::string bytes = pf::EncodePreparedScene(*scene);
        constexpr size_t kHeader = 8 + 4 + 8 + 64;
        std::ofstream(std::string(argv[1]) + "/seed-" + std::to_string(i - 1), std::ios::binary)
            << bytes.substr(kHeader);
    }
    return 0;
}
