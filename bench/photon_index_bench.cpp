// Classic photon mapping's two photon indices against each other, as the first source
// document compares a uniform grid with a kd-tree: for global maps of the Cornell box of
// growing size, the build time and the frames per second of the density estimates alone (one
// k = 64 search per pixel of a 256x256 frame, at points where photons land), on one thread;
// then the grid's figures as ratios of the kd-tree's.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/pm/density_estimate.h"
#include "core/pm/photon_grid.h"
#include "core/pm/photon_map.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

constexpr uint32_t kNearest = 64;
constexpr int kFramePixels = 256 * 256;

// The Cornell box, its global maps' photons by size, and query points (photons of another seed).
struct Fixture {
    Scene scene;
    std::unique_ptr<Emitters> emitters;
    std::unique_ptr<embree::EmbreeTracer> tracer;
    SceneFeatures features;
    std::map<uint64_t, std::vector<StoredPhoton>> photons;
    std::vector<StoredPhoton> queries;
};

Fixture& TheFixture() {
    static Fixture* fixture = [] {
        auto* f = new Fixture;
        absl::StatusOr<Scene> scene =
            LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
        if (!scene.ok()) std::abort();
        f->scene = std::move(*scene);
        f->emitters = std::make_unique<Emitters>(f->scene);
        f->tracer = std::move(*embree::EmbreeTracer::Create(f->scene));
        f->features = AnalyseFeatures(f->scene, *f->emitters);
        PhotonMapSettings settings;
        settings.caustic_photons = 0;
        settings.global_photons = kFramePixels;
        settings.final_gather = 1;  // store every landing, as a global map for final gathering does
        const PhotonMaps maps =
            BuildPhotonMaps(f->scene, *f->emitters, *f->tracer, f->features, settings, 99);
        f->queries.assign(maps.global->Photons().begin(), maps.global->Photons().end());
        return f;
    }();
    return *fixture;
}

const std::vector<StoredPhoton>& PhotonsOf(uint64_t emitted) {
    Fixture& f = TheFixture();
    std::vector<StoredPhoton>& photons = f.photons[emitted];
    if (photons.empty()) {
        PhotonMapSettings settings;
        settings.caustic_photons = 0;
        settings.global_photons = emitted;
        settings.final_gather = 1;
        const PhotonMaps maps =
            BuildPhotonMaps(f.scene, *f.emitters, *f.tracer, f.features, settings, 1);
        photons.assign(maps.global->Photons().begin(), maps.global->Photons().end());
    }
    return photons;
}

std::unique_ptr<PhotonLookup> Build(PhotonIndex index, const std::vector<StoredPhoton>& photons) {
    const Fixture& f = TheFixture();
    const float max_radius = 0.02f * f.scene.bounds.Diagonal();
    return BuildPhotonLookup(
        index, photons,
        GridCellSize(photons.size(), SceneSurfaceArea(f.scene), kNearest, max_radius));
}

void BM_Build(benchmark::State& state, PhotonIndex index) {
    const std::vector<StoredPhoton>& photons = PhotonsOf(uint64_t(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(Build(index, photons));
    state.counters["stored"] = double(photons.size());
}

void BM_Frame(benchmark::State& state, PhotonIndex index) {
    const Fixture& f = TheFixture();
    const std::vector<StoredPhoton>& photons = PhotonsOf(uint64_t(state.range(0)));
    const std::unique_ptr<PhotonLookup> lookup = Build(index, photons);
    const float max_radius = 0.02f * f.scene.bounds.Diagonal();
    NearestPhotons scratch;
    for (auto _ : state) {
        Rgb sum(0.0f);
        for (const StoredPhoton& query : f.queries)
            sum += EstimateDiffuseRadiance(*lookup, query.position, -query.direction, Rgb(0.7f),
                                           kNearest, max_radius * max_radius, DensityFilter::kCone,
                                           false, scratch);
        benchmark::DoNotOptimize(sum);
    }
    state.counters["stored"] = double(photons.size());
    state.counters["fps"] = benchmark::Counter(
        double(kFramePixels) / double(f.queries.size()) * double(state.iterations()),
        benchmark::Counter::kIsRate);
}

void Sizes(benchmark::internal::Benchmark* benchmark) {
    for (int64_t emitted : {10'000, 100'000, 1'000'000, 4'000'000}) benchmark->Arg(emitted);
    benchmark->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_CAPTURE(BM_Build, kdtree, PhotonIndex::kKdTree)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_Build, grid, PhotonIndex::kGrid)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_Frame, kdtree, PhotonIndex::kKdTree)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_Frame, grid, PhotonIndex::kGrid)->Apply(Sizes);

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    // Seconds per run by (kind, index, photons emitted), for the ratios.
    struct Ratios : benchmark::ConsoleReporter {
        std::map<std::string, std::map<std::string, double>>
            seconds;  // "Build/100000" -> index -> s
        std::map<std::string, double> stored;
        void ReportRuns(const std::vector<Run>& runs) override {
            ConsoleReporter::ReportRuns(runs);
            for (const Run& run : runs) {
                const std::string name = run.benchmark_name();  // BM_Frame/grid/100000/real_time
                const size_t first = name.find('/'), second = name.find('/', first + 1),
                             third = name.find('/', second + 1);
                const std::string key =
                    name.substr(3, first - 3) + "/" + name.substr(second + 1, third - second - 1);
                seconds[key][name.substr(first + 1, second - first - 1)] =
                    run.GetAdjustedRealTime();
                stored[key] = run.counters.at("stored");
            }
        }
    } reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    std::printf("\ngrid against kd-tree (time ratio, below 1: the grid is faster)\n");
    for (const auto& [key, by_index] : reporter.seconds)
        if (by_index.contains("grid") && by_index.contains("kdtree"))
            std::printf("  %-16s %10.0f photons stored: %.2f\n", key.c_str(), reporter.stored[key],
                        by_index.at("grid") / by_index.at("kdtree"));
    return 0;
}
