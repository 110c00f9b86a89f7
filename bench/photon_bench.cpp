// Photon pass throughput per thread against the raw Embree ray rate in the same scene, the
// ceiling for photon tracing here. Prints, after the Google Benchmark table, the ratio
// (photon segments traced per second) / (raw rtcIntersect1 rays per second) per scene;
// the target is at least 0.5: the photon pass should cost little beyond its rays. A batch
// also carries one direct-light sample for a slice of the hit points (shadow rays, not photon
// segments); the ratio is given for the photon pass alone and for whole batches. Last, the
// photon pass instantiated for the scene's features (what backends run) against the general
// path, forced, on cornell-box (diffuse only: no specular or texture code), as a ratio. And the
// grid's rebuild over the same hit points, which a worker runs every epoch.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/ppm/hash_grid.h"
#include "core/ppm/photon_pass.h"
#include "core/sampling/rng.h"
#include "core/scene/emitters.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

constexpr int kWidth = 512, kHeight = 512, kSpp = 4;

// A scene ready for photon batches: loaded, traced by Embree, hit points from the camera pass
// at the demo's resolution, grid built for the initial radius.
struct BenchScene {
    Scene scene;
    std::unique_ptr<Emitters> emitters;
    std::unique_ptr<embree::EmbreeTracer> tracer;
    CameraPassResult camera_pass;
    HashGrid grid;
};

BenchScene& Load(const std::string& name) {
    static std::map<std::string, std::unique_ptr<BenchScene>> cache;
    auto& entry = cache[name];
    if (entry) return *entry;
    entry = std::make_unique<BenchScene>();
    absl::StatusOr<Scene> scene =
        LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name + ".gltf");
    if (!scene.ok()) {
        std::fprintf(stderr, "photon_bench: %s\n", std::string(scene.status().message()).c_str());
        std::exit(1);
    }
    entry->scene = std::move(*scene);
    entry->emitters = std::make_unique<Emitters>(entry->scene);
    entry->tracer = std::move(*embree::EmbreeTracer::Create(entry->scene));
    entry->camera_pass =
        RunCameraPass(entry->scene, *entry->emitters, *entry->tracer, {kWidth, kHeight, kSpp, 1});
    const float radius = DefaultInitialRadius(entry->camera_pass, entry->scene);
    const std::vector<float> radius_sq(entry->camera_pass.hit_points.size(), radius * radius);
    entry->grid.Build(entry->camera_pass.hit_points, radius_sq);
    return *entry;
}

// Per second: "pass/<scene>" and "batch/<scene>" photon segments, "rays/<scene>" raw rays.
std::map<std::string, double> g_rates;

// "pass/", "batch/": the photon loop for the scene's features; "general/": the general one.
void BM_PhotonBatch(benchmark::State& state, const std::string& name, bool with_direct,
                    bool general) {
    BenchScene& bench = Load(name);
    const SceneFeatures features =
        general ? SceneFeatures::All() : AnalyseFeatures(bench.scene, *bench.emitters);
    const PhotonPassInputs inputs{&bench.scene,
                                  bench.emitters.get(),
                                  bench.tracer.get(),
                                  bench.camera_pass.hit_points,
                                  &bench.grid,
                                  1,
                                  features};
    PhotonPassScratch scratch;
    tbb::task_arena one_thread(1);
    const BatchLayout layout{kDefaultPhotonsPerBatch, kDefaultBatchesPerEpoch};  // full epochs
    uint64_t segments = 0, photons = 0, epoch = 0;
    double seconds = 0;
    for (auto _ : state) {
        BatchSpec spec = MakeBatchSpec(layout, epoch++, 0,
                                       static_cast<uint32_t>(bench.camera_pass.hit_points.size()));
        if (!with_direct) spec.sample_end = spec.sample_begin;
        const auto start = std::chrono::steady_clock::now();
        BatchResult result;
        one_thread.execute(
            [&] { result = std::move(RunPhotonBatches(inputs, std::span(&spec, 1), scratch)[0]); });
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        segments += result.segments_traced;
        photons += result.photons_emitted;
        benchmark::DoNotOptimize(result.tally.Size());
    }
    state.counters["photons/s"] = benchmark::Counter(double(photons), benchmark::Counter::kIsRate);
    state.counters["segments/s"] =
        benchmark::Counter(double(segments), benchmark::Counter::kIsRate);
    g_rates[(general ? "general/" : with_direct ? "batch/" : "pass/") + name] = segments / seconds;
}

void BM_EmbreeRandomRays(benchmark::State& state, const std::string& name) {
    BenchScene& bench = Load(name);
    const Bounds& bounds = bench.scene.bounds;
    Rng rng(7);
    constexpr int kRays = 1 << 16;
    std::vector<Ray> rays(kRays);
    for (Ray& ray : rays) {
        const Vec3 u(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
        ray.origin = bounds.lower + (bounds.upper - bounds.lower) * u;
        ray.direction = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
    }
    uint64_t traced = 0;
    double seconds = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(bench.tracer->CountHits(rays));
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        traced += kRays;
    }
    state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
    g_rates["rays/" + name] = traced / seconds;
}

// Rebuilding the grid over the demo's hit points, as a worker does every epoch: radii spread
// between half and all of R0, as after a few epochs.
void BM_GridBuild(benchmark::State& state, const std::string& name) {
    BenchScene& bench = Load(name);
    const std::vector<HitPoint>& hit_points = bench.camera_pass.hit_points;
    const float radius = DefaultInitialRadius(bench.camera_pass, bench.scene);
    std::vector<float> radius_sq(hit_points.size());
    Rng rng(3);
    for (float& r2 : radius_sq) r2 = radius * radius * (0.25f + 0.75f * rng.NextFloat());
    HashGrid grid;
    for (auto _ : state) grid.Build(hit_points, radius_sq);
    state.counters["hit points/s"] = benchmark::Counter(
        double(hit_points.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    // One thread: the figures are per thread.
    tbb::global_control single_thread(tbb::global_control::max_allowed_parallelism, 1);
    for (const char* scene : {"cornell-box", "cornell-glass"}) {
        benchmark::RegisterBenchmark((std::string("BM_PhotonPass/") + scene).c_str(),
                                     pf::BM_PhotonBatch, scene, false, false)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(2.0);
        benchmark::RegisterBenchmark((std::string("BM_PhotonBatch/") + scene).c_str(),
                                     pf::BM_PhotonBatch, scene, true, false)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(2.0);
        benchmark::RegisterBenchmark((std::string("BM_EmbreeRandomRays/") + scene).c_str(),
                                     pf::BM_EmbreeRandomRays, scene)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(1.0);
    }
    benchmark::RegisterBenchmark("BM_GridBuild/cornell-box", pf::BM_GridBuild, "cornell-box")
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
    benchmark::RegisterBenchmark("BM_PhotonPassGeneral/cornell-box", pf::BM_PhotonBatch,
                                 "cornell-box", false, true)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2.0);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::printf(
        "\nphoton segments/s per thread over raw rtcIntersect1 rays/s (target: at least 0.5)\n");
    std::printf("%-14s %14s %14s %14s %11s %12s\n", "scene", "pass seg/s", "batch seg/s",
                "raw rays/s", "pass ratio", "batch ratio");
    for (const char* scene : {"cornell-box", "cornell-glass"}) {
        const double pass = pf::g_rates["pass/" + std::string(scene)];
        const double batch = pf::g_rates["batch/" + std::string(scene)];
        const double rays = pf::g_rates["rays/" + std::string(scene)];
        if (pass > 0 && batch > 0 && rays > 0)
            std::printf("%-14s %14.0f %14.0f %14.0f %11.2f %12.2f\n", scene, pass, batch, rays,
                        pass / rays, batch / rays);
    }
    const double specialised = pf::g_rates["pass/cornell-box"],
                 general = pf::g_rates["general/cornell-box"];
    if (specialised > 0 && general > 0)
        std::printf(
            "\ncornell-box photon pass for its features (%s) over the general path: %.3f\n",
            pf::AnalyseFeatures(pf::Load("cornell-box").scene, *pf::Load("cornell-box").emitters)
                .ToString()
                .c_str(),
            specialised / general);
    return 0;
}
