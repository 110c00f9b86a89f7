// The renderable scene in world space: triangles with materials, punctual lights, the camera.
// Immutable after loading; safe to read from many threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry/ray.h"
#include "core/math/vec3.h"
#include "core/sampling/sampling.h"
#include "core/scene/camera.h"
#include "core/scene/material.h"
#include "core/scene/texture.h"

namespace pf {

struct Triangle {
    uint32_t vertex[3];
    uint32_t material;
    bool smooth;    // interpolate vertex normals; otherwise shade with the geometric normal
    Vec3 normal;    // unit geometric normal, on the side counter-clockwise winding makes front
};

enum class LightType : uint32_t { kPoint, kSpot, kDirectional };

// KHR_lights_punctual lights, taken radiometrically: intensity in W/sr for point and spot,
// irradiance in W/m^2 for directional.
struct PunctualLight {
    LightType type = LightType::kPoint;
    Vec3 position;                 // point, spot
    Vec3 direction{0, 0, -1};      // spot, directional: the direction light travels
    Rgb intensity{1.0f};           // colour x intensity
    float cos_inner = 1.0f, cos_outer = 0.7071f;  // spot cone, cosines of the half angles
    bool smooth_falloff = false;   // pbrt's smoothstep between the cones, not glTF's quadratic
    std::string name;

    // The spot's falloff for a direction whose cosine to the axis is cos_axis: glTF's
    // quadratic ramp between the cones, or pbrt's smoothstep.
    float SpotFalloff(float cos_axis) const;
};

struct Bounds {
    Vec3 lower{1e30f}, upper{-1e30f};
    void Extend(const Vec3& p) { lower = Min(lower, p), upper = Max(upper, p); }
    Vec3 Center() const { return (lower + upper) * 0.5f; }
    float Diagonal() const { return Length(upper - lower); }
    // The largest coordinate magnitude, for scale-aware ray offsets (OffsetRayOrigin); at
    // least the smallest normal float, so an empty scene still offsets.
    float Magnitude() const {
        const Vec3 m = Max(Abs(lower), Abs(upper));
        return std::max({m.x, m.y, m.z, std::numeric_limits<float>::min()});
    }
};

// A point on a surface, rebuilt from a ray hit.
struct SurfacePoint {
    Vec3 position;
    Vec3 geometric_normal;  // unit, on the side the triangle's winding makes its front
    Vec3 shading_normal;    // unit, interpolated, on the same side as geometric_normal
    Point2 uv;              // texture coordinates; set only where the material has a texture
    float uv_per_length = 0;  // texture-coordinate units per world length on this triangle; likewise
    uint32_t material = 0;
};

// What a scene file asks of its render (pbrt's Film and Integrator "sppm"), used where the
// render's own settings leave a choice open (JobSpec's FilmFor, EstimateFor); zero or empty
// where the scene says nothing.
struct SceneRenderHints {
    int width = 0, height = 0;
    double initial_radius = 0;        // R0, world units
};

struct Scene {
    std::string source;  // the file it was loaded from, for messages
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // one per position (zero where the mesh had none)
    std::vector<Point2> uvs;    // one per position
    std::vector<Triangle> triangles;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<PunctualLight> lights;
    Camera camera;
    Bounds bounds;
    SceneRenderHints hints;

    SurfacePoint Surface(const RayHit& hit) const;
    // Diffuse reflectance or specular tint at a surface point, texture applied (bilinear, at
    // the point: what a photon meets).
    Rgb BaseColor(const SurfacePoint& surface) const;
    // The same averaged over a footprint `width` world units across (a camera sample's cone
    // where it meets the surface), trilinearly from the texture's MIP levels.
    Rgb BaseColor(const SurfacePoint& surface, float width) const;
    float TriangleArea(uint32_t triangle) const;
};

}  // namespace pf
