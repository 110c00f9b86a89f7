// Tracing and storing classic photon mapping's maps, and what they will cost.
#include "core/pm/photon_map.h"

#include <sys/sysinfo.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <string>

#include "absl/strings/str_format.h"
#include "core/job/job_spec.h"
#include "core/pm/photon_grid.h"
#include "core/pm/photon_kdtree.h"
#include "core/ppm/photon_pass.h"
#include "core/ppm/photon_walk.h"

namespace pf {
namespace {

constexpr uint64_t kGlobalStream = 0x676c6f62616cull;  // "global"
constexpr uint64_t kCausticStream = 0x63617573746963ull + 1;
// Photons traced per task; tasks' photons are concatenated in task order, so the maps do not
// depend on the thread count.
constexpr uint64_t kPhotonsPerTask = 1 << 14;
constexpr uint32_t kPilotPhotons = 1 << 12;
// Besides the photons, a render needs room for the scene, images and the like: a map may use
// this share of the memory available.
constexpr double kMapMemoryShare = 0.75;

enum class MapKind { kGlobal, kCaustic };

// Traces photons [begin, end) of one map and appends what it stores. Global map: photons that
// bounced diffusely at least once, or every landing with final gathering (whose gather rays
// read the whole reflected light there). Caustic map: the first landing after specular or
// rough bounces alone. `per_cosine`: powers per unit of their cosine (ScatterPhotonAt).
template <bool kSpecular, bool kTextures>
void TraceMapPhotons(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                     MapKind kind, bool everything, bool per_cosine, int max_bounces, uint64_t seed,
                     uint64_t begin, uint64_t end, double inverse_emitted,
                     std::vector<StoredPhoton>& out) {
    const SeedFamily seeds(seed, kind == MapKind::kGlobal ? kGlobalStream : kCausticStream, 0);
    for (uint64_t p = begin; p < end; ++p) {
        Rng rng(seeds.Seed(p));
        const EmittedPhoton emitted = emitters.Emit(rng);
        Ray ray = emitted.ray;
        Rgb flux = emitted.flux;
        const PunctualLight* ranged = emitted.ranged;
        int diffuse_bounces = 0, other_bounces = 0;
        for (int bounce = 0; bounce < max_bounces; ++bounce) {
            RayHit hit;
            if (!IsFinite(flux) || !tracer.Intersect(ray, &hit)) break;
            if (ranged != nullptr) {  // the light's range, over the first segment
                flux *= ranged->RangeWindow(hit.t);
                ranged = nullptr;
            }
            bool stop = false;
            const PhotonEvent event = ScatterPhotonAt<kSpecular, kTextures>(
                scene, hit, ray, flux, rng,
                [&](const Vec3& position, const Vec3& direction, const Rgb& power, bool returned,
                    float cosine, const Vec3&) {
                    // With shading normals, per unit of its cosine (EstimateDiffuseRadiance).
                    if (per_cosine && !(cosine > 0)) return;
                    const Rgb stored =
                        power * static_cast<float>(inverse_emitted) / (per_cosine ? cosine : 1.0f);
                    if (kind == MapKind::kCaustic) {
                        if (other_bounces > 0 && diffuse_bounces == 0 && !returned)
                            out.push_back({position, direction, stored});
                        stop = true;  // a caustic photon ends at its first diffuse surface
                    } else if (everything || diffuse_bounces > 0 || returned) {
                        out.push_back({position, direction, stored});
                    }
                });
            if (stop || event == PhotonEvent::kEnded) break;
            (event == PhotonEvent::kDiffuse ? diffuse_bounces : other_bounces) += 1;
        }
    }
}

// Photons [0, count) of one map, in parallel by tasks, concatenated in task order.
std::vector<StoredPhoton> TraceMap(const Scene& scene, const Emitters& emitters,
                                   const Tracer& tracer, const SceneFeatures& features,
                                   MapKind kind, bool everything, int max_bounces, uint64_t seed,
                                   uint64_t count, uint64_t emitted) {
    const auto trace = features.GeneralSurfaces()
                           ? (features.VaryingBaseColor() ? TraceMapPhotons<true, true>
                                                          : TraceMapPhotons<true, false>)
                           : (features.VaryingBaseColor() ? TraceMapPhotons<false, true>
                                                          : TraceMapPhotons<false, false>);
    const uint64_t tasks = (count + kPhotonsPerTask - 1) / kPhotonsPerTask;
    std::vector<std::vector<StoredPhoton>> parts(tasks);
    const double inverse_emitted = emitted > 0 ? 1.0 / static_cast<double>(emitted) : 0.0;
    tbb::parallel_for(uint64_t{0}, tasks, [&](uint64_t t) {
        trace(scene, emitters, tracer, kind, everything, features.ShadingNormals(), max_bounces,
              seed, t * kPhotonsPerTask, std::min(count, (t + 1) * kPhotonsPerTask),
              inverse_emitted, parts[t]);
    });
    size_t total = 0;
    for (const auto& part : parts) total += part.size();
    std::vector<StoredPhoton> photons;
    photons.reserve(total);
    for (auto& part : parts) photons.insert(photons.end(), part.begin(), part.end());
    return photons;
}

// Bytes a lookup of `index` holds per photon (the photon and the index's own arrays).
uint64_t BytesPerPhoton(PhotonIndex index) {
    return sizeof(StoredPhoton) + (index == PhotonIndex::kKdTree ? 1 : 2 * sizeof(uint32_t));
}

}  // namespace

void NearestPhotons::Offer(float distance_sq, uint32_t photon) {
    if (entries.size() < k) {
        entries.push_back({distance_sq, photon});
        std::push_heap(entries.begin(), entries.end());
        if (entries.size() == k) max_distance_sq = entries.front().distance_sq;
        return;
    }
    if (!(distance_sq < entries.front().distance_sq)) return;
    std::pop_heap(entries.begin(), entries.end());
    entries.back() = {distance_sq, photon};
    std::push_heap(entries.begin(), entries.end());
    max_distance_sq = entries.front().distance_sq;
}

PhotonMapForecast ForecastPhotonMaps(const Scene& scene, const Emitters& emitters,
                                     const Tracer& tracer, const SceneFeatures& features,
                                     const PhotonMapSettings& settings, uint64_t seed,
                                     int max_depth) {
    PhotonMapForecast forecast;
    const int max_bounces = DepthLimit(max_depth, kMaxPhotonBounces);
    const bool everything = settings.final_gather > 0;
    // The pilot's own streams: the maps' first photons would do too, but then the pilot and
    // the maps would share their luck.
    const uint64_t pilot_seed = HashSeed(seed, 0x70696c6f74ull);
    forecast.global_stored_per_emitted =
        double(TraceMap(scene, emitters, tracer, features, MapKind::kGlobal, everything,
                        max_bounces, pilot_seed, kPilotPhotons, 1)
                   .size()) /
        kPilotPhotons;
    if (features.Specular())
        forecast.caustic_stored_per_emitted =
            double(TraceMap(scene, emitters, tracer, features, MapKind::kCaustic, false,
                            max_bounces, pilot_seed, kPilotPhotons, 1)
                       .size()) /
            kPilotPhotons;
    const double stored = forecast.global_stored_per_emitted * double(settings.global_photons) +
                          forecast.caustic_stored_per_emitted * double(settings.caustic_photons);
    forecast.bytes = static_cast<uint64_t>(stored * double(BytesPerPhoton(settings.index)));
    return forecast;
}

uint64_t AvailableMemoryBytes() {
    struct sysinfo info {};
    uint64_t available = sysinfo(&info) == 0 ? uint64_t(info.totalram) * info.mem_unit : UINT64_MAX;
    // A container's limit (cgroup v2, then v1): "max" or a number of bytes.
    for (const char* path :
         {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(path);
        std::string limit;
        if (in >> limit && !limit.empty() && std::isdigit(static_cast<unsigned char>(limit[0])))
            available = std::min<uint64_t>(available, std::stoull(limit));
    }
    return available;
}

absl::Status CheckPhotonMapsFit(const PhotonMapForecast& forecast,
                                const PhotonMapSettings& settings, uint64_t available) {
    const double allowed = kMapMemoryShare * static_cast<double>(available);
    if (static_cast<double>(forecast.bytes) <= allowed) return absl::OkStatus();
    const double gib = 1024.0 * 1024.0 * 1024.0;
    return absl::ResourceExhaustedError(absl::StrFormat(
        "--pm-photons/--pm-caustic-photons: %d + %d photons would store about %.3g GiB of photon "
        "maps (%.2f and %.2f "
        "photons stored per photon emitted), over the %.3g GiB this machine can spare (%.0f%% of "
        "%.3g GiB); emit "
        "fewer, or use a progressive integrator (ppm, sppm), whose memory does not grow with "
        "photons",
        settings.global_photons, settings.caustic_photons, double(forecast.bytes) / gib,
        forecast.global_stored_per_emitted, forecast.caustic_stored_per_emitted, allowed / gib,
        100 * kMapMemoryShare, double(available) / gib));
}

std::unique_ptr<PhotonLookup> BuildPhotonLookup(PhotonIndex index,
                                                std::vector<StoredPhoton> photons,
                                                float cell_size) {
    if (index == PhotonIndex::kGrid)
        return std::make_unique<PhotonGrid>(std::move(photons), cell_size);
    return std::make_unique<PhotonKdTree>(std::move(photons));
}

float MaxSearchRadius(const PhotonMapSettings& settings, const Scene& scene) {
    return settings.max_radius > 0 ? static_cast<float>(settings.max_radius)
                                   : 0.02f * scene.bounds.Diagonal();
}

double SceneSurfaceArea(const Scene& scene) {
    double area = 0;
    for (uint32_t t = 0; t < scene.WorldTriangleCount(); ++t) area += scene.TriangleArea(t);
    for (uint32_t c = 0; c < scene.WorldCurveCount(); ++c) area += scene.curves[c].Area();
    for (const Instance& instance : scene.instances) {
        const Prototype& prototype = scene.prototypes[instance.prototype];
        double prototype_area = 0;
        for (uint32_t c = prototype.first_curve; c < prototype.first_curve + prototype.curve_count;
             ++c)
            prototype_area += scene.curves[c].Area();
        for (uint32_t t = prototype.first_triangle;
             t < prototype.first_triangle + prototype.triangle_count; ++t) {
            const Triangle& triangle = scene.triangles[t];
            const Vec3& p0 = scene.positions[triangle.vertex[0]];
            prototype_area += 0.5 * Length(Cross(scene.positions[triangle.vertex[1]] - p0,
                                                 scene.positions[triangle.vertex[2]] - p0));
        }
        // Areas scale by |det|^(2/3) under a uniform scale, the common case.
        const std::array<float, 12>& m = instance.to_world;
        const double det = double(m[0]) * (double(m[5]) * m[10] - double(m[6]) * m[9]) -
                           double(m[1]) * (double(m[4]) * m[10] - double(m[6]) * m[8]) +
                           double(m[2]) * (double(m[4]) * m[9] - double(m[5]) * m[8]);
        area += prototype_area * std::pow(std::abs(det), 2.0 / 3.0);
    }
    return area;
}

PhotonMaps BuildPhotonMaps(const Scene& scene, const Emitters& emitters, const Tracer& tracer,
                           const SceneFeatures& features, const PhotonMapSettings& settings,
                           uint64_t seed, int max_depth) {
    PhotonMaps maps;
    const int max_bounces = DepthLimit(max_depth, kMaxPhotonBounces);
    maps.global_emitted = settings.global_photons;
    maps.caustic_emitted = features.Specular() ? settings.caustic_photons : 0;
    const float max_radius = MaxSearchRadius(settings, scene);
    const double area = SceneSurfaceArea(scene);
    std::vector<StoredPhoton> global =
        TraceMap(scene, emitters, tracer, features, MapKind::kGlobal, settings.final_gather > 0,
                 max_bounces, seed, maps.global_emitted, maps.global_emitted);
    std::vector<StoredPhoton> caustic =
        TraceMap(scene, emitters, tracer, features, MapKind::kCaustic, false, max_bounces, seed,
                 maps.caustic_emitted, maps.caustic_emitted);
    const float global_cell = GridCellSize(global.size(), area, settings.nearest, max_radius);
    const float caustic_cell = GridCellSize(caustic.size(), area, settings.nearest, max_radius);
    maps.global = BuildPhotonLookup(settings.index, std::move(global), global_cell);
    maps.caustic = BuildPhotonLookup(settings.index, std::move(caustic), caustic_cell);
    return maps;
}

}  // namespace pf
