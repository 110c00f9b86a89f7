// The coordinator's merge rate: tallies of real batches (cornell-box, 512x512x4 spp, one epoch
// of 8 batches of 2^19 photons) are recorded once, then replayed through the coordinator's
// path: decoding the wire message (as ReportTally does) and folding into the estimate, then
// finishing the epoch. Prints hit-point updates (tally entries) per second, the entries a
// batch produces per photon at the default batch size and at a farm's (2^24 photons, one
// batch recorded), and from both how many 16-core workers one coordinator can keep merged at
// full speed (the arithmetic is in docs/farm.md).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "core/camera/camera_pass.h"
#include "core/estimate/progressive_estimate.h"
#include "core/job/job_spec.h"
#include "core/scene/emitters.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "wire/blob_codec.h"
#include "wire/proto_convert.h"
#include "worker/backend_factory.h"

namespace pf {
namespace {

struct Recorded {
    Scene scene;
    CameraPassResult camera_pass;
    EstimateSettings settings;
    std::vector<BatchResult> results;
    std::vector<std::string> wire;  // the same results as ReportTally requests carry them
    double radii_bytes = 0, hit_point_bytes = 0;  // blob sizes per hit point
    double batch_seconds = 0;                     // one batch on one thread
    uint64_t entries = 0;
    double farm_entries_per_photon = 0,
           farm_wire_bytes_per_photon = 0;  // a batch of kFarmBatch photons
};

// A farm's batch: 32 chunks, spread over a worker's threads and summed there.
constexpr uint32_t kFarmBatch = 1u << 24;

Recorded& Record() {
    static std::unique_ptr<Recorded> recorded;
    if (recorded) return *recorded;
    recorded = std::make_unique<Recorded>();
    Recorded& r = *recorded;
    r.scene = *LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    std::shared_ptr<const Tracer> tracer = std::move(*embree::EmbreeTracer::Create(r.scene));
    JobSpec spec;
    spec.width = spec.height = 512;
    spec.samples_per_pixel = 4;
    spec.seed = 1;
    spec.photon_budget = 1;
    const CameraPassSettings film = *FilmFor(spec, r.scene);
    r.camera_pass = RunCameraPass(r.scene, Emitters(r.scene), *tracer, film);
    r.settings = EstimateFor(spec, r.camera_pass, r.scene, "cornell-box");
    ProgressiveEstimate estimate(r.camera_pass, r.settings, {});
    const Emitters emitters(r.scene);
    std::unique_ptr<Backend> backend = std::move(*CreateBackend("cpu", r.scene));
    (void)backend->BeginJob({&r.scene, &emitters, estimate.HitPoints(), 1, &spec});
    (void)backend->BeginEpoch(estimate.Epoch(), estimate.Regions(), nullptr);
    const std::vector<BatchSpec> specs = estimate.EpochBatches();
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        const auto start = std::chrono::steady_clock::now();
        r.results.push_back((*backend->RunBatches(std::span(specs).first(1)))[0]);
        r.batch_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    std::vector<BatchResult> rest = *backend->RunBatches(std::span(specs).subspan(1));
    for (BatchResult& result : rest) r.results.push_back(std::move(result));
    // After the first epoch every reached hit point has the same radius (R^2 alpha); a few
    // real epochs later they have spread out as in any long run.
    estimate.MergeEpoch(r.results);
    for (int epoch = 1; epoch < 4; ++epoch) {
        (void)backend->BeginEpoch(estimate.Epoch(), estimate.Regions(), nullptr);
        estimate.MergeEpoch(*backend->RunBatches(estimate.EpochBatches()));
    }
    {
        BatchSpec farm = estimate.EpochBatches()[0];
        farm.photons = kFarmBatch;
        const BatchResult result = std::move((*backend->RunBatches(std::span(&farm, 1)))[0]);
        r.farm_entries_per_photon = double(result.tally.Size()) / kFarmBatch;
        r.farm_wire_bytes_per_photon = double(ToProto(result).ByteSizeLong()) / kFarmBatch;
    }
    r.radii_bytes =
        double(EncodeGatherRegions(estimate.Regions()).size()) / estimate.HitPoints().size();
    r.hit_point_bytes =
        double(EncodeHitPoints(estimate.HitPoints()).size()) / estimate.HitPoints().size();
    for (const BatchResult& result : r.results) {
        r.wire.push_back(ToProto(result).SerializeAsString());
        r.entries += result.tally.Size();
    }
    return r;
}

// Folding one epoch's recorded results (their emission pass's shares too) and finishing it, as
// the coordinator does.
// The fold and the update run on the job's thread with TBB's help: range(0) threads.
void BM_MergeEpoch(benchmark::State& state) {
    Recorded& r = Record();
    ProgressiveEstimate estimate(r.camera_pass, r.settings, {});
    tbb::task_arena arena(static_cast<int>(state.range(0)));
    for (auto _ : state)
        arena.execute([&] {
            for (uint32_t j = 0; j < r.results.size();
                 ++j) {  // replayed as the next epoch's batches
                r.results[j].spec.epoch = estimate.Epoch();
                r.results[j].spec.index = estimate.Epoch() * r.results.size() + j;
                estimate.FoldBatch(r.results[j]);
            }
            estimate.FinishEpoch();
        });
    state.counters["updates/s"] =
        benchmark::Counter(double(r.entries) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MergeEpoch)
    ->Arg(1)
    ->Arg(tbb::this_task_arena::max_concurrency())
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Parsing and checking the ReportTally payloads of one epoch, on one thread (the coordinator
// decodes each report on its own gRPC handler thread, so several decode at once).
void BM_DecodeEpoch(benchmark::State& state) {
    Recorded& r = Record();
    const uint32_t hit_points = static_cast<uint32_t>(r.camera_pass.hit_points.size());
    for (auto _ : state) {
        for (const std::string& bytes : r.wire) {
            photonfarm::v1::BatchResult message;
            message.ParseFromString(bytes);
            benchmark::DoNotOptimize(FromProto(message, hit_points, hit_points));
        }
    }
    state.counters["updates/s"] =
        benchmark::Counter(double(r.entries) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DecodeEpoch)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    pf::Recorded& r = pf::Record();
    struct Rates : benchmark::ConsoleReporter {
        double merge_one = 0, merge_all = 0, decode = 0;
        void ReportRuns(const std::vector<Run>& runs) override {
            ConsoleReporter::ReportRuns(runs);
            for (const Run& run : runs) {
                const double rate = run.counters.at("updates/s");
                if (run.benchmark_name().find("Merge") == std::string::npos)
                    decode = rate;
                else if (run.benchmark_name().find("MergeEpoch/1/") != std::string::npos)
                    merge_one = rate;
                else
                    merge_all = rate;
            }
        }
    } reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    const double wire_bytes = [&] {
        double b = 0;
        for (const auto& w : r.wire) b += w.size();
        return b;
    }();
    const double photons = double(r.results.size()) * r.results[0].photons_emitted;
    const double entries_per_photon = double(r.entries) / photons;
    const int threads = tbb::this_task_arena::max_concurrency();
    // Every report is decoded on some thread and folded with all of them: per update, the
    // decode's share of the threads plus the fold.
    const double coordinator_rate =
        1.0 / (1.0 / (reporter.decode * threads) + 1.0 / reporter.merge_all);
    const double photons_per_core = r.results[0].photons_emitted / r.batch_seconds;
    const double worker_rate = 16.0 * photons_per_core * entries_per_photon;
    const double farm_worker_rate = 16.0 * photons_per_core * r.farm_entries_per_photon;
    std::printf(
        "\nmerge: %.3g hit-point updates/s on 1 thread, %.3g on %d; decode: %.3g/s per thread; "
        "coordinator on %d threads: %.3g/s\n",
        reporter.merge_one, reporter.merge_all, threads, reporter.decode, threads,
        coordinator_rate);
    std::printf(
        "a batch: %.3g photons/s on one thread, %.3f tally entries per photon, %.2f wire bytes per "
        "photon "
        "(%.1f per entry)\n",
        r.results[0].photons_emitted / r.batch_seconds, entries_per_photon, wire_bytes / photons,
        wire_bytes / r.entries);
    std::printf(
        "blobs: hit points %.2f bytes each (once per job), squared radii %.2f bytes each (once per "
        "epoch)\n",
        r.hit_point_bytes, r.radii_bytes);
    std::printf(
        "a batch of 2^24 photons (a farm's layout): %.4f tally entries per photon, %.3f wire bytes "
        "per photon\n",
        r.farm_entries_per_photon, r.farm_wire_bytes_per_photon);
    for (const auto& [layout, rate] :
         {std::pair{"2^19-photon batches", worker_rate}, {"2^24-photon batches", farm_worker_rate}})
        std::printf(
            "%s: a 16-core worker makes %.3g updates/s; this coordinator (%d threads) merges for "
            "%.1f such "
            "workers, a 16-thread one for about %.0f (scaled by threads)\n",
            layout, rate, threads, coordinator_rate / rate,
            coordinator_rate / rate * 16.0 / threads);
    return 0;
}
