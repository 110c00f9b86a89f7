// Transforming curve segments into the scene.
#include "core/scene/curve_builder.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/util/check.h"

namespace pf {

absl::Status AppendCurves(const std::vector<Curve>& curves, const Transform& world, bool reverse,
                          const SceneLimits& limits, const std::string& element, Scene* scene,
                          std::optional<uint32_t> prototype) {
    PF_CHECK(!prototype || (*prototype + 1 == scene->prototypes.size() &&
                            scene->prototypes[*prototype].first_curve +
                                    scene->prototypes[*prototype].curve_count ==
                                scene->curves.size()));
    if (scene->curves.size() + curves.size() > limits.max_curves)
        return absl::ResourceExhaustedError(
            absl::StrCat(element, ": the scene would hold more than ", limits.max_curves,
                         " curve segments, the loading limit"));
    Bounds& bounds = prototype ? scene->prototypes[*prototype].bounds : scene->bounds;
    const double scale = std::cbrt(std::abs(world.Determinant()));
    for (size_t c = 0; c < curves.size(); ++c) {
        Curve placed = curves[c];
        bool distinct = false;
        for (Vec3& p : placed.control) {
            p = Vec3(world.ApplyPoint(Vec3d(p)));
            if (!IsFinite(p))
                return absl::InvalidArgumentError(absl::StrCat(
                    element, ": curve segment ", c, " is not finite after its transform"));
            distinct |= p != placed.control[0];
        }
        for (float& w : placed.width) w = static_cast<float>(w * scale);
        if (!distinct || !(placed.width[0] > 0 || placed.width[1] > 0)) continue;
        if (!std::isfinite(placed.width[0]) || !std::isfinite(placed.width[1]))
            return absl::InvalidArgumentError(absl::StrCat(
                element, ": curve segment ", c, "'s width is not finite after its transform"));
        for (Vec3& n : placed.normal) {
            const Vec3d mapped = world.ApplyNormal(Vec3d(n));
            n = LengthSquared(mapped) > 0 && IsFinite(mapped) ? Vec3(Normalize(mapped))
                                                              : Vec3(0.0f);
            if (reverse) n = -n;
        }
        if (placed.type == CurveType::kRibbon &&
            (LengthSquared(placed.normal[0]) == 0 || LengthSquared(placed.normal[1]) == 0))
            return absl::InvalidArgumentError(
                absl::StrCat(element, ": curve segment ", c, " has a zero normal"));
        const Bounds box = placed.Box();
        bounds.Extend(box.lower), bounds.Extend(box.upper);
        scene->curves.push_back(placed);
        if (prototype) ++scene->prototypes[*prototype].curve_count;
    }
    return absl::OkStatus();
}

}  // namespace pf
