// What a coordinator's checkpoint of a progressive photon mapping job costs: cornell-box at
// 512x512 and 4 spp, three real epochs of 8 batches of 2^19 photons and half of a fourth (a
// checkpoint between folds carries the epoch's sums), saved and loaded as Job::Checkpoint and
// Job::Restore do: whole, and with the hit points apart (kept once per job). Prints bytes per
// hit point and milliseconds, and fails unless every state loaded saves to the same bytes.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>

#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "worker/backend_factory.h"

namespace pf {
namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Folds `batches` of the current epoch's batches, run by `backend`.
void RunBatches(Backend& backend, ProgressiveEstimate& estimate, size_t batches) {
    if (estimate.BatchesFolded() == 0)
        (void)backend.BeginEpoch(estimate.Epoch(), estimate.Regions(), nullptr);
    const std::vector<BatchSpec> specs = estimate.EpochBatches();
    absl::StatusOr<std::vector<BatchResult>> results =
        backend.RunBatches(std::span(specs).subspan(estimate.BatchesFolded(), batches));
    if (!results.ok()) {
        std::fprintf(stderr, "checkpoint_bench: %s\n",
                     std::string(results.status().message()).c_str());
        std::exit(1);
    }
    for (const BatchResult& result : *results) estimate.FoldBatch(result);
    if (estimate.BatchesFolded() == specs.size()) estimate.FinishEpoch();
}

// Saves the estimate and loads it back, printing bytes per hit point and times; false unless
// the state loaded saves to the same bytes.
bool Report(const char* what, const ProgressiveEstimate& estimate, FixedPart part,
            const std::string* fixed) {
    auto start = std::chrono::steady_clock::now();
    ByteWriter state;
    estimate.Save(state, part);
    const double save_seconds = Seconds(start);
    start = std::chrono::steady_clock::now();
    ByteReader reader(state.Bytes());
    ByteReader fixed_reader(fixed != nullptr ? std::string_view(*fixed) : std::string_view());
    absl::StatusOr<std::unique_ptr<ProgressiveEstimate>> loaded =
        ProgressiveEstimate::Load(reader, fixed != nullptr ? &fixed_reader : nullptr);
    const double load_seconds = Seconds(start);
    ByteWriter again;
    if (loaded.ok()) (*loaded)->Save(again, part);
    const bool same = loaded.ok() && again.Bytes() == state.Bytes();
    std::printf("%-44s %6.1f bytes per hit point; saved in %4.0f ms, loaded in %4.0f ms%s\n", what,
                double(state.Bytes().size()) / double(estimate.HitPoints().size()),
                1e3 * save_seconds, 1e3 * load_seconds, same ? "" : " (NOT LOADED AS SAVED)");
    return same;
}

int Run() {
    const Scene scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    std::shared_ptr<const Tracer> tracer = std::move(*embree::EmbreeTracer::Create(scene));
    JobSpec spec;
    spec.width = spec.height = 512;
    spec.samples_per_pixel = 4;
    spec.seed = 1;
    spec.photon_budget = 1;
    const CameraPassSettings film = *FilmFor(spec, scene);
    CameraPassResult camera_pass = RunCameraPass(scene, Emitters(scene), *tracer, film);
    ProgressiveEstimate estimate(camera_pass, EstimateFor(spec, camera_pass, scene, "cornell"), {});
    const Emitters emitters(scene);
    std::unique_ptr<Backend> backend = std::move(*CreateBackend("cpu", scene));
    (void)backend->BeginJob({&scene, &emitters, estimate.HitPoints(), 1, &spec});
    const size_t batches = estimate.Settings().layout.batches_per_epoch;
    for (int epoch = 0; epoch < 3; ++epoch) RunBatches(*backend, estimate, batches);
    RunBatches(*backend, estimate, batches / 2);

    const double hit_points = double(estimate.HitPoints().size());
    std::printf("%.0f hit points, epoch %llu, %u batches of it folded\n", hit_points,
                static_cast<unsigned long long>(estimate.Epoch()), estimate.BatchesFolded());
    bool ok = Report("state, hit points included", estimate, FixedPart::kIncluded, nullptr);
    ByteWriter fixed;
    auto start = std::chrono::steady_clock::now();
    estimate.SaveFixed(fixed);
    std::printf("%-44s %6.1f bytes per hit point; saved in %4.0f ms\n",
                "hit points alone (once per job)", double(fixed.Bytes().size()) / hit_points,
                1e3 * Seconds(start));
    ok &= Report("state, hit points apart (every checkpoint)", estimate, FixedPart::kApart,
                 &fixed.Bytes());
    RunBatches(*backend, estimate, batches - estimate.BatchesFolded());
    ok &= Report("the same at the epoch's end", estimate, FixedPart::kApart, &fixed.Bytes());
    return ok ? 0 : 1;
}

}  // namespace
}  // namespace pf

int main() {
    try {
        return pf::Run();
    } catch (const std::exception& error) {
        std::fprintf(stderr, "checkpoint_bench: %s\n", error.what());
        return 1;
    }
}
