// The light transport algorithms photonfarm runs (`--integrator`), and the settings of the
// one that stores photons, classic photon mapping. Every integrator runs as epochs of
// batches through the same coordinator and workers; they differ in what a batch computes and
// how the coordinator folds it (docs/integrators.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pf {

enum class Integrator : uint32_t {
    // Progressive photon mapping (Hachisuka et al. 2008): hit points traced once, per-point
    // N, R, tau; batches shoot photons.
    kPpm,
    // Stochastic progressive photon mapping (Hachisuka & Jensen 2009): hit points traced anew
    // every epoch, N, R, tau per pixel sample.
    kSppm,
    // Classic photon mapping (Jensen 1996): global and caustic photon maps stored once,
    // k-nearest density estimation; batches render pixels.
    kPm,
    // Unidirectional path tracing with next-event estimation and multiple importance
    // sampling: the unbiased reference; batches render pixels.
    kPath,
    // Reverse photon mapping (Havran, Herzog & Seidel 2005): each epoch's camera samples trace
    // their final-gather rays first and keep where they land as hit points; batches shoot
    // photons into them (never stored). Classic photon mapping's final-gather estimate, its
    // radii fixed (PhotonMapSettings: the global map's k nearest), at a cost that grows with
    // the photons rather than with gather rays x k-nearest searches.
    kRpm,
};

std::string_view IntegratorName(Integrator integrator);
std::optional<Integrator> ParseIntegrator(std::string_view name);
std::vector<std::string> IntegratorNames();  // "pm", "ppm", "sppm", "rpm", "path", for --help

// Whether the integrator's batches shoot photons into hit points (ppm, sppm, rpm) rather than
// render pixels (pm, path).
inline bool GathersAtHitPoints(Integrator integrator) {
    return integrator == Integrator::kPpm || integrator == Integrator::kSppm ||
           integrator == Integrator::kRpm;
}
// Whether its hit points are traced anew every epoch, by the coordinator and every worker
// alike (sppm's camera samples, rpm's with their gather hits), rather than once (ppm).
inline bool TracesHitPointsEachEpoch(Integrator integrator) {
    return integrator == Integrator::kSppm || integrator == Integrator::kRpm;
}

// The photon backends a worker can run on (`--backend`; worker/backend_factory.h makes them):
// "cpu" (Embree, the default) and "vulkan" (compute kernels).
inline std::vector<std::string> BackendNames() { return {"cpu", "vulkan"}; }

// How ppm and sppm trace photons (`--photon-tracing`): independent photons, or Markov chains
// toward the photons that reach a hit point (adaptive photon tracing, Hachisuka & Jensen 2011;
// core/shared/photon_chain.h). Auto: the coordinator chooses adaptive where a pilot finds few
// photons reaching a hit point (kAdaptiveBelowVisibleShare) and tells the workers which.
enum class PhotonTracing : uint32_t { kAuto, kUniform, kAdaptive };

std::string_view PhotonTracingName(PhotonTracing tracing);
std::optional<PhotonTracing> ParsePhotonTracing(std::string_view name);

// How classic photon mapping finds a point's nearest photons.
enum class PhotonIndex : uint32_t { kKdTree, kGrid };
// How it weights them in the density estimate (Jensen 2001, section 7.1).
// Numbered as core/shared/density_filter.h's kFilter*.
enum class DensityFilter : uint32_t { kBox, kCone, kGaussian };

std::string_view PhotonIndexName(PhotonIndex index);
std::optional<PhotonIndex> ParsePhotonIndex(std::string_view name);
std::string_view DensityFilterName(DensityFilter filter);
std::optional<DensityFilter> ParseDensityFilter(std::string_view name);

// Final-gather rays a camera sample of rpm traces where PhotonMapSettings::final_gather is 0.
// Each is a hit point of the epoch (pixels x k x (1 + rays) of them, the camera sample's own
// included), so memory grows with them.
inline constexpr uint32_t kRpmGatherRays = 4;

// Classic photon mapping's settings (and reverse photon mapping's: its radii are those the
// global map's k nearest reach, its gather rays `final_gather`). The maps are built once per job
// (on every worker, from the job's seed, so every worker holds the same maps) and kept in memory:
// their size grows with the photons emitted, and PhotonMapBytes says how much.
struct PhotonMapSettings {
    uint64_t global_photons = 1'000'000;  // emitted for the global map (indirect light)
    uint64_t caustic_photons =
        1'000'000;          // emitted for the caustic map (light through specular chains)
    uint32_t nearest = 64;  // k: photons per density estimate
    double max_radius = 0;  // of the k-nearest search, world units; 0: 2% of the scene's diagonal
    DensityFilter filter = DensityFilter::kCone;
    uint32_t final_gather =
        0;  // gather rays per camera sample for indirect light; 0: read the global map directly
    PhotonIndex index = PhotonIndex::kKdTree;
};

// The gather rays of each rpm camera sample.
inline uint32_t RpmGatherRays(const PhotonMapSettings& settings) {
    return settings.final_gather > 0 ? settings.final_gather : kRpmGatherRays;
}

}  // namespace pf
