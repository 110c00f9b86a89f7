// Job flags.
#include "client/job_options.h"

#include <map>
#include <string>

#include "core/util/command_line.h"

namespace pf {

void AddJobOptions(CLI::App* command, JobSpec* s) {
    const auto count = CLI::AsNumberWithUnit(
        std::map<std::string, uint64_t>{{"k", 1000}, {"m", 1000000}, {"g", 1000000000}, {"t", 1000000000000}},
        CLI::AsNumberWithUnit::CASE_INSENSITIVE, "COUNT");
    auto* photons = command->add_option("--photons", s->photon_budget, "Photon budget, e.g. 20M (finishes the epoch that reaches it; default 20M)")
                        ->transform(count);
    command->add_option("--seconds", s->seconds_budget, "Time budget in seconds (finishes the epoch that reaches it)")
        ->check(FinitePositive())->excludes(photons);
    command->add_option("--target-error", s->target_error,
                        "Stop once the estimated relative error (from even and odd batches) is at most this, e.g. "
                        "0.02; with --photons or --seconds, whichever comes first")
        ->check(FiniteRange(1e-9, 999.0));
    command->add_option("--photons-per-batch", s->layout.photons_per_batch, "Photon paths per batch, the unit of work")
        ->default_val(s->layout.photons_per_batch)->check(CLI::Range(1u, kMaxPhotonsPerBatch));
    command->add_option("--batches-per-epoch", s->layout.batches_per_epoch,
                        "Batches per epoch; radii shrink once per epoch, and a farm runs at most this many batches at once")
        ->default_val(s->layout.batches_per_epoch)->check(CLI::Range(1u, kMaxBatchesPerEpoch));
    // capture_default_str, not default_val: default_val would re-parse "0.666667" into alpha,
    // and the render would no longer match a farm job left at the default 2/3.
    command->add_option("--alpha", s->alpha, "Radius reduction ratio alpha in (0, 1]")->capture_default_str()->check(FiniteRange(1e-9, 1.0));
    command->add_option("--radius", s->initial_radius, "Initial search radius R0, world units (default: one pixel footprint)")
        ->check(FinitePositive());
    command->add_option("--spp", s->samples_per_pixel, "Hit points (camera paths) per pixel")->default_val(s->samples_per_pixel)
        ->check(CLI::Range(1, 1024));
    command->add_option("--seed", s->seed, "Random seed; the same seed and batch layout give the same image")->default_val(s->seed);
    command->add_option("--photon-stream", s->photon_stream,
                        "Another photon stream of the same --seed: the same hit points, independent photons "
                        "(to render a reference for --reference)")
        ->default_val(s->photon_stream);
    command->add_option("--width", s->width, "Image width in pixels (default: the scene's own (a pbrt Film), else 512)")->check(CLI::Range(1, 32768));
    command->add_option("--height", s->height, "Image height in pixels (default: width / camera aspect)")->check(CLI::Range(1, 32768));
}

void ApplyDefaultBudget(JobSpec* spec) {
    if (spec->photon_budget == 0 && spec->seconds_budget == 0 && spec->target_error == 0) spec->photon_budget = 20'000'000;
}

}  // namespace pf
