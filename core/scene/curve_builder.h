// Appending curves, given in their own space, to a Scene (its world, or a prototype that
// instances place): the one place for what placing a curve takes (its points and normals
// transformed, its width scaled, the limit on how many a scene holds).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "core/math/transform.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"

namespace pf {

// Appends `curves` (their own space; material and type as given, ribbons' normals unit) placed
// by `world` to the world or, given `prototype`, to that prototype, which must be the last
// begun (`world` then maps into its space). Control points map as points, ribbons' normals as
// normals (flipped by `reverse`, pbrt's ReverseOrientation), widths by the cube root of
// |det(world)| (exact for a uniform scale). A curve whose points all coincide or whose widths
// are both 0 is dropped. Errors name `element`: a point not finite after the transform, the
// curve limit exceeded (RESOURCE_EXHAUSTED).
absl::Status AppendCurves(const std::vector<Curve>& curves, const Transform& world, bool reverse,
                          const SceneLimits& limits, const std::string& element, Scene* scene,
                          std::optional<uint32_t> prototype = std::nullopt);

}  // namespace pf
