// Job flags.
#include "client/job_options.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/util/command_line.h"

namespace pf {

namespace {

// An enum flag given by name: the names checked (the error lists them), then turned into the
// enum's value.
template <typename Enum>
void EnumChoices(CLI::Option* option, const std::vector<std::string>& names,
                 std::optional<Enum> (*parse)(std::string_view)) {
    std::map<std::string, std::string> values;
    for (const std::string& name : names)
        values.emplace(name, std::to_string(static_cast<int>(*parse(name))));
    const std::string choices = "{" + CLI::detail::join(names, ",") + "}";
    option->transform(CLI::Validator(
        [values, choices](std::string& input) -> std::string {
            const auto it = values.find(CLI::detail::to_lower(input));
            if (it == values.end()) return input + " not in " + choices;
            input = it->second;
            return std::string();
        },
        choices));
}

void AddPhotonMapOptions(CLI::App* command, PhotonMapSettings* m) {
    command
        ->add_option(
            "--pm-photons", m->global_photons,
            "pm: photons emitted for the global map. The maps are kept in memory, about 40 bytes "
            "per "
            "photon stored (a photon is stored at every diffuse bounce): a count that will not fit "
            "is refused")
        ->capture_default_str()
        ->transform(CountWithUnit(0, kMaxMapPhotons));
    command
        ->add_option(
            "--pm-caustic-photons", m->caustic_photons,
            "pm: photons emitted for the caustic map (those reaching a diffuse surface through "
            "specular bounces are stored)")
        ->capture_default_str()
        ->transform(CountWithUnit(0, kMaxMapPhotons));
    command
        ->add_option("--pm-nearest", m->nearest,
                     "pm: k, photons per density estimate (rpm: its radii reach the k nearest "
                     "of a --pm-photons global map)")
        ->capture_default_str()
        ->check(WholeNumber(1, kMaxNearestPhotons));
    command
        ->add_option(
            "--pm-max-radius", m->max_radius,
            "pm, rpm: largest radius of the nearest-photon search, world units (default: 2% of "
            "the scene's "
            "diagonal)")
        ->check(FinitePositive());
    EnumChoices(command->add_option("--pm-filter", m->filter, "pm: density estimation filter")
                    ->default_str("cone"),
                {"box", "cone", "gaussian"}, ParseDensityFilter);
    command
        ->add_option("--final-gather", m->final_gather,
                     "pm, rpm: gather rays per camera sample for indirect light (pm's 0: read the "
                     "global map directly; rpm's 0: 4)")
        ->capture_default_str()
        ->check(WholeNumber(0, kMaxFinalGatherRays));
    EnumChoices(
        command->add_option("--photon-index", m->index, "pm: how photons are stored and searched")
            ->default_str("kdtree"),
        {"kdtree", "grid"}, ParsePhotonIndex);
}

void AddEnvironmentOptions(CLI::App* command, EnvironmentSettings* e) {
    auto* file = command->add_option(
        "--environment", e->file,
        "Light the scene from far away with this latitude-longitude image (.exr, .hdr, ...; "
        "its centre straight ahead along -z, +y up), in place of the scene's own environment");
    file->check(CLI::ExistingFile);
    command
        ->add_option_function<std::vector<double>>(
            "--environment-color",
            [e](const std::vector<double>& rgb) {
                e->color = Rgb(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]),
                               static_cast<float>(rgb[2]));
            },
            "Light the scene from far away with this uniform radiance R,G,B in W/(m^2 sr)")
        ->delimiter(',')
        ->expected(3)
        ->check(FiniteRange(0.0, kMaxEnvironmentScale))
        ->excludes(file);
    command
        ->add_option("--environment-scale", e->scale,
                     "Multiplies the environment's radiance (--environment or --environment-color)")
        ->capture_default_str()
        ->check(FiniteRange(1e-30, kMaxEnvironmentScale));
    command
        ->add_option("--environment-rotate", e->rotate_degrees,
                     "Turns the environment about the up axis (+y) by this many degrees")
        ->capture_default_str()
        ->check(FiniteRange(-360.0, 360.0));
}

}  // namespace

void AddJobOptions(CLI::App* command, JobSpec* s) {
    EnumChoices(
        command
            ->add_option(
                "--integrator", s->integrator,
                "Light transport: ppm (progressive photon mapping), sppm (stochastic ppm), pm "
                "(classic photon mapping, maps stored in memory), rpm (reverse photon mapping: "
                "photons splatted into final-gather hits), path (path tracing, the unbiased "
                "reference); docs/integrators.md")
            ->default_str("ppm"),
        IntegratorNames(), ParseIntegrator);
    auto* photons =
        command
            ->add_option(
                "--photons", s->photon_budget,
                "Photon budget of ppm, sppm and rpm, e.g. 20M (finishes the epoch that reaches it; "
                "default 20M)")
            ->transform(CountWithUnit(1, kMaxPhotonBudget));
    auto* epochs =
        command
            ->add_option("--epochs", s->epoch_budget,
                         "Epoch budget: stop after this many (default for path and pm: 16)")
            ->check(WholeNumber(1, kMaxEpochBudget));
    auto* seconds = command
                        ->add_option("--seconds", s->seconds_budget,
                                     "Time budget in seconds (finishes the epoch that reaches it)")
                        ->check(FiniteRange(1e-3, kMaxSecondsBudget))
                        ->excludes(photons);
    auto* target_error =
        command
            ->add_option("--target-error", s->target_error,
                         "Stop once the estimated relative error (from even and odd batches) is at "
                         "most this, e.g. "
                         "0.02; with --photons or --seconds, whichever comes first")
            ->check(FiniteRange(1e-9, 999.0));
    command
        ->add_flag("--until-cancelled", s->until_cancelled,
                   "No budget: render until stopped (Ctrl-C, or `photonfarm cancel` on a farm)")
        ->excludes(photons)
        ->excludes(epochs)
        ->excludes(seconds)
        ->excludes(target_error);
    command
        ->add_option("--photons-per-batch", s->layout.photons_per_batch,
                     "Photon paths per batch, the unit of work (default: ppm 524288; sppm and "
                     "rpm one photon per camera sample of an epoch, in batches of 32768)")
        ->check(WholeNumber(1, kMaxPhotonsPerBatch));
    command
        ->add_option("--batches-per-epoch", s->layout.batches_per_epoch,
                     "Batches per epoch; radii shrink once per epoch, and a farm runs at most this "
                     "many batches at once (default: 8; sppm and rpm as many as their photons "
                     "need)")
        ->check(WholeNumber(1, kMaxBatchesPerEpoch));
    command
        ->add_option("--first-epoch-photons", s->layout.first_epoch_photons,
                     "Small epochs first: the first epoch's photons, each later one twice the one "
                     "before until a full epoch, e.g. 256K (default: ppm 256K with the layout "
                     "left open; otherwise every epoch full)")
        ->transform(CountWithUnit(1, uint64_t{kMaxPhotonsPerBatch} * kMaxBatchesPerEpoch));
    EnumChoices(command
                    ->add_option("--photon-tracing", s->photon_tracing,
                                 "ppm, sppm, rpm (uniform only): independent photons, or Markov "
                                 "chains toward the "
                                 "photons that reach what the camera sees (adaptive: for light "
                                 "through a gap, a caustic in an open scene); auto chooses "
                                 "adaptive where a pilot finds under 5% reach it")
                    ->default_str("auto"),
                {"auto", "uniform", "adaptive"}, ParsePhotonTracing);
    command
        ->add_option("--alpha", s->alpha,
                     "ppm, sppm: radius reduction ratio alpha in (0, 1] for every epoch "
                     "(default: balanced, each epoch's chosen in [0.55, 0.95] from the estimated "
                     "bias and noise, 2/3 where they balance)")
        ->default_str("balanced")
        ->check(FiniteRange(1e-9, 1.0));
    command
        ->add_option("--radius", s->initial_radius,
                     "Initial search radius R0, world units, for every hit point (default: each "
                     "its own, from a pilot photon map's density)")
        ->check(FinitePositive());
    command
        ->add_option("--spp", s->samples_per_pixel,
                     "Camera paths per pixel: hit points (ppm), hit points per epoch (sppm), "
                     "samples per epoch (path, pm, rpm: each with its gather rays)")
        ->default_val(s->samples_per_pixel)
        ->check(WholeNumber(1, 1024));
    command
        ->add_option("--seed", s->seed,
                     "Random seed; the same seed and batch layout give the same image")
        ->default_val(s->seed)
        ->check(WholeNumber(0, UINT64_MAX));
    command
        ->add_option(
            "--photon-stream", s->photon_stream,
            "Another photon stream of the same --seed: the same hit points, independent photons "
            "(to render a reference for --reference)")
        ->default_val(s->photon_stream)
        ->check(WholeNumber(0, UINT64_MAX));
    command
        ->add_option("--width", s->width,
                     "Image width in pixels (default: the scene's own (a pbrt Film), else 512)")
        ->check(WholeNumber(1, 32768));
    command
        ->add_option("--height", s->height,
                     "Image height in pixels (default: width / camera aspect)")
        ->check(WholeNumber(1, 32768));
    command
        ->add_option("--max-depth", s->max_depth,
                     "Most surfaces a path scatters at, as pbrt's maxdepth (default: the scene's "
                     "Integrator, else no limit but Russian roulette)")
        ->check(WholeNumber(1, kMaxDepthSetting));
    AddPhotonMapOptions(command, &s->photon_map);
    AddEnvironmentOptions(command, &s->environment);
    command->add_option("--camera", s->camera,
                        "Which of a glTF scene's cameras renders: its number (0 first, in the "
                        "node hierarchy's order) or its node's or camera's name (default: the "
                        "first; a scene without one is framed on its bounds)");
}

GivenSettings GivenSettingsOf(const CLI::App& command) {
    return {command.count("--integrator") > 0, command.count("--spp") > 0,
            command.count("--photons-per-batch") + command.count("--batches-per-epoch") > 0,
            command.count("--max-depth") > 0};
}

}  // namespace pf
