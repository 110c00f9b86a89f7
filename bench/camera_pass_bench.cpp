// The workers' emission pass of a ppm epoch (EmissionCameraPass: the emission the camera
// sees, at the epoch's fresh camera samples), alone and crediting each sample's diffuse hit to
// the fixed hit points it stands for (CameraPassResult::coverage), on cornell-box at 256x256,
// 4 fixed hit points a pixel, a full epoch's samples a pixel in the default layout (32); on all
// threads. Prints the ratio of the two times (medians where repeated): what the hit points'
// shares of their pixels cost an epoch's pass.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <string>

#include "core/camera/camera_pass.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

struct Setup {
    Scene scene;
    std::unique_ptr<Emitters> emitters;
    std::shared_ptr<const Tracer> tracer;
    JobSpec spec;
    CameraPassSettings film;
    std::shared_ptr<const PixelHitPoints> fixed;
};

Setup& Get() {
    static std::unique_ptr<Setup> setup;
    if (setup) return *setup;
    setup = std::make_unique<Setup>();
    Setup& s = *setup;
    s.scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    s.emitters = std::make_unique<Emitters>(s.scene);
    s.tracer = std::move(*embree::EmbreeTracer::Create(s.scene));
    s.spec.integrator = Integrator::kPpm;
    s.spec.width = s.spec.height = 256;
    s.spec.samples_per_pixel = 4;
    s.spec.seed = 1;
    s.film = *FilmFor(s.spec, s.scene);
    s.film.features = AnalyseFeatures(s.scene, *s.emitters);
    s.fixed = std::make_shared<const PixelHitPoints>(PixelHitPoints::Index(
        std::make_shared<const std::vector<HitPoint>>(
            RunCameraPass(s.scene, *s.emitters, *s.tracer, s.film).hit_points),
        size_t(s.film.width) * size_t(s.film.height)));
    return s;
}

// A full epoch's pass (the growing epochs take fewer samples); range(0): crediting the fixed
// hit points or not.
void BM_EmissionPass(benchmark::State& state) {
    Setup& s = Get();
    const uint64_t full =
        ResolvedLayout(s.spec, uint64_t(s.film.width) * s.film.height).GrowingEpochs();
    const CameraPassSettings pass = EmissionCameraPass(s.film, s.spec, full);
    const PixelHitPoints* fixed = state.range(0) != 0 ? s.fixed.get() : nullptr;
    for (auto _ : state)
        benchmark::DoNotOptimize(RunCameraPass(s.scene, *s.emitters, *s.tracer, pass, fixed));
    state.counters["samples/pixel"] = pass.samples_per_pixel;
}
BENCHMARK(BM_EmissionPass)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    struct Times : benchmark::ConsoleReporter {
        double alone = 0, crediting = 0;
        void ReportRuns(const std::vector<Run>& runs) override {
            ConsoleReporter::ReportRuns(runs);
            for (const Run& run : runs)
                if (run.aggregate_name.empty() || run.aggregate_name == "median")
                    (run.benchmark_name().find("/1") != std::string::npos ? crediting : alone) =
                        run.GetAdjustedRealTime();
        }
    } reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    if (reporter.alone > 0 && reporter.crediting > 0)
        std::printf("\ncrediting the fixed hit points / the pass alone: %.3f\n",
                    reporter.crediting / reporter.alone);
    benchmark::Shutdown();
    return 0;
}
