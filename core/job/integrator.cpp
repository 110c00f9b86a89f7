// Integrator, photon index and filter names for flags, messages and metadata.
#include "core/job/integrator.h"

#include <array>
#include <utility>

namespace pf {
namespace {

template <typename Enum, size_t kCount>
std::optional<Enum> Parse(const std::array<std::pair<Enum, std::string_view>, kCount>& names,
                          std::string_view name) {
    for (const auto& [value, value_name] : names)
        if (value_name == name) return value;
    return std::nullopt;
}

template <typename Enum, size_t kCount>
std::string_view Name(const std::array<std::pair<Enum, std::string_view>, kCount>& names,
                      Enum value) {
    for (const auto& [candidate, name] : names)
        if (candidate == value) return name;
    return "unknown";
}

constexpr std::array<std::pair<Integrator, std::string_view>, 5> kIntegrators{
    {{Integrator::kPm, "pm"},
     {Integrator::kPpm, "ppm"},
     {Integrator::kSppm, "sppm"},
     {Integrator::kRpm, "rpm"},
     {Integrator::kPath, "path"}}};
constexpr std::array<std::pair<PhotonTracing, std::string_view>, 3> kTracings{
    {{PhotonTracing::kAuto, "auto"},
     {PhotonTracing::kUniform, "uniform"},
     {PhotonTracing::kAdaptive, "adaptive"}}};
constexpr std::array<std::pair<PhotonIndex, std::string_view>, 2> kIndices{
    {{PhotonIndex::kKdTree, "kdtree"}, {PhotonIndex::kGrid, "grid"}}};
constexpr std::array<std::pair<DensityFilter, std::string_view>, 3> kFilters{
    {{DensityFilter::kBox, "box"},
     {DensityFilter::kCone, "cone"},
     {DensityFilter::kGaussian, "gaussian"}}};

}  // namespace

std::string_view IntegratorName(Integrator integrator) { return Name(kIntegrators, integrator); }
std::optional<Integrator> ParseIntegrator(std::string_view name) {
    return Parse(kIntegrators, name);
}
std::vector<std::string> IntegratorNames() {
    std::vector<std::string> names;
    for (const auto& entry : kIntegrators) names.emplace_back(entry.second);
    return names;
}

std::string_view PhotonTracingName(PhotonTracing tracing) { return Name(kTracings, tracing); }
std::optional<PhotonTracing> ParsePhotonTracing(std::string_view name) {
    return Parse(kTracings, name);
}
std::string_view PhotonIndexName(PhotonIndex index) { return Name(kIndices, index); }
std::optional<PhotonIndex> ParsePhotonIndex(std::string_view name) { return Parse(kIndices, name); }
std::string_view DensityFilterName(DensityFilter filter) { return Name(kFilters, filter); }
std::optional<DensityFilter> ParseDensityFilter(std::string_view name) {
    return Parse(kFilters, name);
}

}  // namespace pf
