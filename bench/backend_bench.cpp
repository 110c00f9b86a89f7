// Photon throughput of every backend on the same batches, in one run: photon paths and path
// segments per second through the Backend interface (what a worker runs), on cornell-box and
// cornell-glass at the demo's resolution, after a warm-up batch. Prints the Vulkan/CPU ratio.
// On a machine without a GPU the Vulkan figures are lavapipe's (a regression check, not a
// speed claim); on a GPU this is the command docs/vulkan.md gives:
//   ./build/bench/backend_bench [--seconds S] [--photons-per-batch N] [--backends cpu,vulkan]
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "absl/strings/str_split.h"
#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "core/util/command_line.h"
#include "embree/embree_tracer.h"
#include "worker/backend_factory.h"

namespace pf {
namespace {

struct Rate {
    double photons_per_second = 0, segments_per_second = 0;
};

// Runs batches of `photons` each, all of one epoch's radii, for about `seconds`.
absl::StatusOr<Rate> Measure(const std::string& backend_name, const std::string& scene_name,
                             uint32_t photons, double seconds) {
    absl::StatusOr<Scene> scene =
        LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + scene_name + ".gltf");
    if (!scene.ok()) return scene.status();
    std::shared_ptr<const Tracer> tracer = std::move(*embree::EmbreeTracer::Create(*scene));
    JobSpec spec;
    spec.width = spec.height = 512;
    spec.samples_per_pixel = 4;
    spec.seed = 1;
    spec.photon_budget = 1;
    spec.layout = {photons, 8};
    const CameraPassSettings film = *FilmFor(spec, *scene);
    const CameraPassResult camera_pass = RunCameraPass(*scene, Emitters(*scene), *tracer, film);
    const ProgressiveEstimate estimate(camera_pass,
                                       EstimateFor(spec, camera_pass, *scene, scene_name), {});
    const Emitters emitters(*scene);
    absl::StatusOr<std::unique_ptr<Backend>> backend = CreateBackend(backend_name, *scene);
    if (!backend.ok()) return backend.status();
    if (absl::Status status =
            (*backend)->BeginJob({&*scene, &emitters, estimate.HitPoints(), 1, &spec});
        !status.ok())
        return status;
    if (absl::Status status = (*backend)->BeginEpoch(estimate.Epoch(), estimate.Regions(), nullptr);
        !status.ok())
        return status;
    const std::vector<BatchSpec> batches = estimate.EpochBatches();
    if (absl::StatusOr<std::vector<BatchResult>> warm =
            (*backend)->RunBatches(std::span(batches).first(1));
        !warm.ok())
        return warm.status();
    uint64_t photons_run = 0, segments = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0;
    for (size_t next = 0; elapsed < seconds; next = (next + 1) % batches.size()) {
        absl::StatusOr<std::vector<BatchResult>> results =
            (*backend)->RunBatches(std::span(batches).subspan(next, 1));
        if (!results.ok()) return results.status();
        photons_run += (*results)[0].photons_emitted;
        segments += (*results)[0].segments_traced;
        elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return Rate{photons_run / elapsed, segments / elapsed};
}

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    CLI::App app{"backend_bench: photon throughput of each backend on the same batches"};
    double seconds = 5;
    uint32_t photons = 1u << 19;
    std::string backends = "cpu,vulkan";
    app.add_option("--seconds", seconds, "Seconds per backend and scene")
        ->check(pf::FiniteRange(0.01, 3600.0));
    app.add_option("--photons-per-batch", photons, "Photons per batch")
        ->check(pf::WholeNumber(1, pf::kMaxPhotonsPerBatch));
    app.add_option("--backends", backends, "Comma-separated backends");
    CLI11_PARSE(app, argc, argv);
    std::printf("%-14s %-8s %16s %18s\n", "scene", "backend", "photons/s", "segments/s");
    for (const char* scene : {"cornell-box", "cornell-glass"}) {
        std::map<std::string, double> segments;
        for (const std::string& backend : std::vector<std::string>(absl::StrSplit(backends, ','))) {
            const absl::StatusOr<pf::Rate> rate = pf::Measure(backend, scene, photons, seconds);
            if (!rate.ok()) {
                std::printf("%-14s %-8s unavailable: %s\n", scene, backend.c_str(),
                            std::string(rate.status().message()).c_str());
                continue;
            }
            std::printf("%-14s %-8s %16.0f %18.0f\n", scene, backend.c_str(),
                        rate->photons_per_second, rate->segments_per_second);
            segments[backend] = rate->segments_per_second;
        }
        if (segments["cpu"] > 0 && segments["vulkan"] > 0)
            std::printf("%-14s vulkan/cpu segments per second: %.3f (cpu on %d threads)\n", scene,
                        segments["vulkan"] / segments["cpu"],
                        tbb::this_task_arena::max_concurrency());
    }
    return 0;
}
