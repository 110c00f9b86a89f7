// Every shipped scene (scenes/*.gltf, scenes/pbrt/*.pbrt) renders, with every integrator on the
// CPU backend, the very image recorded from an earlier commit: a refactoring of light transport
// must not change one bit. The images are kept as SHA-256 digests of their pixels in
// tests/golden/cpu_images.txt, written by tests/golden/record.sh from a named commit (its
// header says which); a render that differs fails naming the scene, the integrator and that
// commit, and the script renders both sides as EXR files to look at.
//
// Bit for bit across machines: Embree is held to SSE4.2 (PF_EMBREE_CONFIG) and glibc's maths
// library to its baseline versions (GLIBC_TUNABLES, read at exec: the test runs itself again
// with it), so a CPU with AVX-512 or FMA renders what one without them does.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/film/exr_io.h"
#include "core/job/integrator.h"
#include "core/util/sha256.h"
#include "embedded/local_render.h"

namespace pf {
namespace {

constexpr char kTunables[] = "GLIBC_TUNABLES";
// Every maths-library variant chosen by a CPU feature (libm's FMA, FMA4, AVX2 and AVX-512
// versions of exp, log, pow, sin, cos ...) masked, leaving the x86-64 baseline's.
constexpr char kBaselineMaths[] = "glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4,-AVX512F,-AVX512DQ";
constexpr char kEmbreeBaseline[] = "isa=sse4.2";

// Runs this process again with kBaselineMaths in its environment, before any test: the
// dynamic loader reads GLIBC_TUNABLES only at exec.
[[maybe_unused]] const bool kBaselineMathsInEffect = [] {
    const char* tunables = std::getenv(kTunables);
    if (tunables != nullptr && std::strstr(tunables, kBaselineMaths) != nullptr) return true;
    std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
    std::vector<std::string> args;
    for (std::string arg; std::getline(cmdline, arg, '\0');) args.push_back(arg);
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    setenv(kTunables, kBaselineMaths, 1);
    execv("/proc/self/exe", argv.data());
    std::perror("golden_images_test: exec with GLIBC_TUNABLES");
    std::exit(1);
}();

std::string SourceDir() { return PF_SOURCE_DIR; }
std::string ManifestPath() { return SourceDir() + "/tests/golden/cpu_images.txt"; }

// Whether a pbrt file is a scene rather than a part that scenes Include (cornell-room.pbrt).
bool IsWholeScene(const std::filesystem::path& path) {
    std::ifstream file(path);
    const std::string text{std::istreambuf_iterator<char>(file), {}};
    return text.find("WorldBegin") != std::string::npos;
}

// The shipped scenes as paths relative to scenes/, sorted.
std::vector<std::string> ShippedScenes() {
    std::vector<std::string> scenes;
    for (const char* folder : {"", "pbrt/"})
        for (const auto& entry :
             std::filesystem::directory_iterator(SourceDir() + "/scenes/" + folder)) {
            const std::string extension = entry.path().extension().string();
            if (extension == ".gltf" || (extension == ".pbrt" && IsWholeScene(entry.path())))
                scenes.push_back(folder + entry.path().filename().string());
        }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

// A render small enough that 145 of them take about a minute, yet reaching every part of each
// integrator: several epochs (radii shrink, sppm and rpm trace new hit points), light paths of
// every depth, 32x24 pixels (a transposed image differs).
RenderSettings GoldenRender(const std::string& scene, Integrator integrator) {
    RenderSettings settings;
    settings.scene_path = SourceDir() + "/scenes/" + scene;
    settings.threads = 2;
    settings.given = {
        .integrator = true, .samples_per_pixel = true, .layout = true, .max_depth = true};
    JobSpec& job = settings.job;
    // A glTF scene under a sky has it beside it (scenes/generate_scenes.py), as
    // `photonfarm render scenes/NAME.gltf --environment scenes/NAME-sky.hdr` renders it.
    const std::string sky =
        SourceDir() + "/scenes/" + scene.substr(0, scene.rfind('.')) + "-sky.hdr";
    if (std::filesystem::exists(sky)) job.environment.file = sky;
    job.integrator = integrator;
    job.width = 32;
    job.height = 24;
    job.seed = 7;
    job.samples_per_pixel = 2;
    job.layout = {1u << 13, 4};
    switch (integrator) {
        case Integrator::kPpm:
        case Integrator::kSppm:
        case Integrator::kRpm:
            job.photon_budget = 3u << 15;  // three epochs of 2^15
            break;
        case Integrator::kPm:
            job.photon_map.global_photons = 20'000;
            job.photon_map.caustic_photons = 20'000;
            job.epoch_budget = 2;
            break;
        case Integrator::kPath:
            job.epoch_budget = 3;
            break;
    }
    return settings;
}

// The digest of an image's size and pixels, each channel's float bytes in memory order.
std::string PixelDigest(const Image& image) {
    Sha256 digest;
    digest.Update(std::to_string(image.width) + "x" + std::to_string(image.height) + "\n");
    for (const Rgb& pixel : image.pixels)
        for (const float channel : {pixel.x, pixel.y, pixel.z})
            digest.Update(
                std::string_view(reinterpret_cast<const char*>(&channel), sizeof channel));
    return digest.HexDigest();
}

struct Manifest {
    std::string recorded_from;                                           // the header's first line
    std::map<std::pair<std::string, std::string>, std::string> digests;  // (scene, integrator)
};

Manifest ReadManifest() {
    Manifest manifest;
    std::ifstream file(ManifestPath());
    for (std::string line; std::getline(file, line);) {
        if (line.rfind("# recorded from ", 0) == 0) manifest.recorded_from = line.substr(2);
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::string scene, integrator, digest;
        fields >> scene >> integrator >> digest;
        manifest.digests[{scene, integrator}] = digest;
    }
    return manifest;
}

class GoldenImages : public ::testing::TestWithParam<std::string> {};

// Renders the scene with each integrator and either appends its digests to the file named by
// PF_GOLDEN_RECORD (tests/golden/record.sh) or compares them with the manifest's.
TEST_P(GoldenImages, EveryIntegratorRendersTheRecordedImage) {
    setenv("PF_EMBREE_CONFIG", kEmbreeBaseline, 1);
    const char* record = std::getenv("PF_GOLDEN_RECORD");
    const Manifest manifest = ReadManifest();
    if (record == nullptr) {
        ASSERT_FALSE(manifest.digests.empty()) << "cannot read " << ManifestPath();
    }
    for (const std::string& name : IntegratorNames()) {
        const Integrator integrator = *ParseIntegrator(name);
        const absl::StatusOr<RenderOutcome> outcome =
            RenderLocally(GoldenRender(GetParam(), integrator));
        ASSERT_TRUE(outcome.ok()) << GetParam() << " " << name << ": " << outcome.status();
        const std::string digest = PixelDigest(outcome->image);
        if (const char* images = std::getenv("PF_GOLDEN_IMAGES")) {  // record.sh --images
            std::string file = GetParam() + "-" + name + ".exr";
            std::replace(file.begin(), file.end(), '/', '-');
            ASSERT_TRUE(WriteExr(std::string(images) + "/" + file, outcome->image).ok());
        }
        if (record != nullptr) {
            std::ofstream(record, std::ios::app)
                << GetParam() << " " << name << " " << digest << "\n";
            continue;
        }
        const auto recorded = manifest.digests.find({GetParam(), name});
        if (recorded == manifest.digests.end()) {
            ADD_FAILURE() << GetParam() << " " << name << ": no image recorded in "
                          << ManifestPath() << " (tests/golden/record.sh records them)";
            continue;
        }
        EXPECT_EQ(digest, recorded->second)
            << GetParam() << " with " << name << " renders another image than the one "
            << manifest.recorded_from
            << "; tests/golden/record.sh --commit REV --images DIR writes either side's renders";
    }
}

std::string CaseName(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Shipped, GoldenImages, ::testing::ValuesIn(ShippedScenes()), CaseName);

// Every recorded scene is still shipped: a scene renamed or removed is recorded again.
TEST(GoldenImagesManifest, NamesOnlyShippedScenes) {
    const std::vector<std::string> scenes = ShippedScenes();
    for (const auto& [key, digest] : ReadManifest().digests)
        EXPECT_TRUE(std::find(scenes.begin(), scenes.end(), key.first) != scenes.end())
            << key.first << " is recorded but not shipped";
}

}  // namespace
}  // namespace pf
