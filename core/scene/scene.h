// The renderable scene in world space: triangles with materials, punctual lights, the camera,
// and prototypes placed by instances. Immutable after loading; safe to read from many threads.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/film/film_response.h"
#include "core/geometry/ray.h"
#include "core/math/transform.h"
#include "core/math/vec3.h"
#include "core/sampling/sampling.h"
#include "core/scene/camera.h"
#include "core/scene/environment.h"
#include "core/scene/material.h"
#include "core/scene/texture.h"

namespace pf {

struct Triangle {
    uint32_t vertex[3];
    uint32_t material;
    bool smooth;  // interpolate vertex normals; otherwise shade with the geometric normal
    Vec3 normal;  // unit geometric normal, on the side counter-clockwise winding makes front
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

// A curve's cross-section (pbrt-v4's curve "type"; gpu::kCurve*).
enum class CurveType : uint32_t { kFlat = 0, kCylinder = 1, kRibbon = 2 };

// One cubic Bezier segment of a curve (pbrt-v4's "curve" shape: hair, fur, grass), in world
// space or a prototype's: a band whose width varies linearly along it. Flat and cylinder curves
// face the ray that meets them (a cylinder shades as a round tube); a ribbon is a band whose
// normal turns from one end's to the other's. What a hit on one is: core/shared/curve.h.
struct Curve {
    std::array<Vec3, 4> control;  // Bezier control points
    std::array<float, 2> width;   // at u = 0 and u = 1, finite, >= 0, not both 0
    std::array<Vec3, 2> normal;   // a ribbon's unit normals at u = 0 and 1 (its front's side)
    uint32_t material = 0;
    CurveType type = CurveType::kFlat;

    // The largest half-width, and the box around the band.
    float Radius() const { return 0.5f * std::max(width[0], width[1]); }
    Bounds Box() const;
    // pbrt-v4's Curve::Area: the control polygon's length times the mean width.
    float Area() const;
};

enum class LightType : uint32_t { kPoint, kSpot, kDirectional, kGoniometric, kProjection };

// KHR_lights_punctual lights, taken radiometrically: intensity in W/sr for point and spot,
// irradiance in W/m^2 for directional; and pbrt's lights that shape a point light's intensity
// by an image (goniometric, projection).
struct PunctualLight {
    LightType type = LightType::kPoint;
    Vec3 position;                                // point, spot
    Vec3 direction{0, 0, -1};                     // spot, directional: the direction light travels
    Rgb intensity{1.0f};                          // colour x intensity
    float cos_inner = 1.0f, cos_outer = 0.7071f;  // spot cone, cosines of the half angles
    bool smooth_falloff = false;  // pbrt's smoothstep between the cones, not glTF's quadratic
    // glTF's range (point, spot): beyond it the light gives nothing, and it fades toward it by
    // the window the glTF specification recommends. 0: no range.
    float range = 0;
    // Goniometric and projection: the intensity toward a direction is `intensity` times this
    // image's nearest texel there. Goniometric: an equal-area octahedral square over the light's
    // sphere of directions (pbrt-v4's). Projection: a picture projected along the light's +z
    // through a frustum whose shorter side spans +-tan_half_fov at distance 1, its top row
    // toward the light's -y (pbrt-v4's ProjectionLight, which flips y).
    std::shared_ptr<const Texture> image;
    std::array<float, 9> to_light{1, 0, 0, 0, 1, 0, 0, 0, 1};  // world into the light's frame
    float tan_half_fov = 1;
    std::string name;

    // The spot's falloff for a direction whose cosine to the axis is cos_axis: glTF's
    // quadratic ramp between the cones, or pbrt's smoothstep.
    float SpotFalloff(float cos_axis) const;
    // The range's window at `distance` (core/shared/path_sampling.h); 1 without a range.
    float RangeWindow(float distance) const { return gpu::RangeWindow(distance, range); }
    bool HasImage() const {
        return type == LightType::kGoniometric || type == LightType::kProjection;
    }
    // The light's direction `toward` (unit, world) in its own frame.
    Vec3 ToLight(const Vec3& toward) const;
    // Projection: the image's half-width and half-height on the plane z = 1 of the light's
    // frame (its shorter side spans +-tan_half_fov), and the point of that plane at image
    // position (x, y), in texels from its top left.
    Point2 ProjectionExtent() const;
    Vec3 ProjectionPlanePoint(float x, float y) const;
    // Goniometric, projection: the image's factor toward unit world direction `toward` (0
    // outside a projection's frustum).
    Rgb ImageFactor(const Vec3& toward) const;
};

// A vertex's colour (glTF's COLOR_0): linear RGB and alpha, each in [0, 1].
struct VertexColor {
    Rgb rgb{1.0f};
    float alpha = 1.0f;
};

// A point on a surface, rebuilt from a ray hit.
struct SurfacePoint {
    Vec3 position;
    Vec3 geometric_normal;  // unit, on the side the triangle's winding makes its front
    Vec3 shading_normal;    // unit, interpolated, on the same side as geometric_normal
    Point2 uv;              // texture coordinates; set only where the material reads them
    float uv_per_length =
        0;            // texture-coordinate units per world length on this triangle; likewise
    Rgb color{1.0f};  // the vertex colours interpolated (Scene::colors; white without)
    uint32_t material = 0;
};

// A mesh stored once, in its own space, and placed any number of times by instances (pbrt's
// ObjectBegin/ObjectInstance, a glTF mesh that several nodes use): triangles
// [first_triangle, first_triangle + triangle_count) of Scene::triangles, which hold it in that
// space, and its curves likewise. Prototypes follow the world's own triangles
// (Scene::WorldTriangleCount) and curves, and hold no emitters: emitting shapes are always
// placed as world triangles.
struct Prototype {
    uint32_t first_triangle = 0, triangle_count = 0;
    uint32_t first_curve = 0, curve_count = 0;  // of Scene::curves, likewise
    Bounds bounds;                              // in the prototype's space
};

// A prototype placed in the world: an affine object-to-world map, in float as tracing applies it.
struct Instance {
    static constexpr uint32_t kNone = ~0u;
    uint32_t prototype = 0;
    std::array<float, 12> to_world{};   // row-major 3x4: [linear | translation]
    std::array<float, 9> normal_map{};  // row-major 3x3: the inverse transpose of the linear part,
                                        // up to a positive scale (normals keep their side)

    // from_object must be invertible and finite (AddInstance checks).
    static Instance Make(uint32_t prototype, const Transform& from_object);
    Vec3 ApplyPoint(const Vec3& p) const {
        const float* m = to_world.data();
        return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
                m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
    }
    // The linear part alone (a tangent's map).
    Vec3 ApplyVector(const Vec3& v) const {
        const float* m = to_world.data();
        return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
                m[8] * v.x + m[9] * v.y + m[10] * v.z};
    }
    // Not normalised.
    Vec3 ApplyNormal(const Vec3& n) const {
        const float* m = normal_map.data();
        return {m[0] * n.x + m[1] * n.y + m[2] * n.z, m[3] * n.x + m[4] * n.y + m[5] * n.z,
                m[6] * n.x + m[7] * n.y + m[8] * n.z};
    }
};

// What a scene file asks of its render (pbrt's Film and Integrator "sppm"), used where the
// render's own settings leave a choice open (JobSpec's FilmFor, EstimateFor); zero or empty
// where the scene says nothing.
struct SceneRenderHints {
    int width = 0, height = 0;
    double initial_radius = 0;  // R0, world units
};

// What a scene file asks of its render (pbrt's Integrator and Sampler directives), for
// ApplySceneSettings (core/job/scene_settings.h); zero or empty where the scene says nothing.
struct SceneRenderSettings {
    std::string integrator;              // an --integrator name (IntegratorNames)
    int pixel_samples = 0;               // camera samples per pixel over the whole render
    uint64_t iterations = 0;             // sppm: epochs
    uint64_t photons_per_iteration = 0;  // sppm: photons per epoch
    int max_depth = 0;                   // JobSpec::max_depth
    // Where each came from ("scene.pbrt:3:1: Integrator \"sppm\""), for the notes.
    std::string integrator_source, sampler_source;
};

struct Scene {
    std::string source;  // the file it was loaded from, for messages
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // one per position (zero where the mesh had none)
    std::vector<Point2> uvs;    // one per position
    // One per position where a material has a normal map (Scene::NeedsTangents), else empty:
    // unit, along increasing u (zero where the mesh needs none); the bitangent's side is each
    // triangle's own (core/scene/tangents.h).
    std::vector<Vec3> tangents;
    // One per position where some mesh has vertex colours (glTF's COLOR_0; white for the
    // vertices of meshes without), else empty: they multiply the base colour, and the alpha
    // and emission where the material says so (Material::surface_flags).
    std::vector<VertexColor> colors;
    std::vector<Triangle> triangles;  // the world's own, then each prototype's (in its space)
    std::vector<Curve> curves;        // likewise; never emitting
    std::vector<Prototype> prototypes;
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<std::shared_ptr<const Texture>> textures;  // shared with texture_filter
    std::shared_ptr<const TextureFilter>
        texture_filter;  // set by the loaders where there are textures
    std::vector<PunctualLight> lights;
    std::optional<Environment> environment;  // light from infinitely far away, if any
    Camera camera;
    // What the film makes of the radiance (pbrt's Film iso, whitebalance; the camera's
    // shutter): applied to the job's images. Not in prepared scenes: workers never need it.
    FilmResponse film;
    Bounds bounds;  // of everything, instances included
    SceneRenderHints hints;
    SceneRenderSettings render_settings;  // pbrt's Integrator and Sampler; not prepared

    // Triangles [0, WorldTriangleCount()) are in world space; the prototypes' follow.
    uint32_t WorldTriangleCount() const {
        return prototypes.empty() ? static_cast<uint32_t>(triangles.size())
                                  : prototypes.front().first_triangle;
    }

    uint32_t WorldCurveCount() const {
        return prototypes.empty() ? static_cast<uint32_t>(curves.size())
                                  : prototypes.front().first_curve;
    }
    // A curve as it lies in the world: placed by `instance` (Instance::kNone: a world curve),
    // its widths scaled by the instance's mean scale (the cube root of its determinant).
    Curve WorldCurve(uint32_t curve, uint32_t instance) const;

    // The surface point a ray hit: its material resolved through mixes (Material::kMix).
    SurfacePoint Surface(const RayHit& hit) const;
    // Material `m`, or where it is a mix, the one it is at `position` on `triangle` (texture
    // coordinates `uv` and geometric normal `normal`, read where a mix's amount has a texture).
    uint32_t ResolveMaterial(uint32_t m, const Vec3& position, uint32_t triangle,
                             const Point2& uv = {}, const Vec3& normal = {}) const {
        if (materials[m].type != MaterialType::kMix) [[likely]]
            return m;
        return ResolveMix(m, position, triangle, uv, normal);
    }
    uint32_t ResolveMix(uint32_t m, const Vec3& position, uint32_t triangle, const Point2& uv,
                        const Vec3& normal) const;
    // Texture `texture` (an index into textures) at `surface`: an image's bilinear lookup at its
    // coordinates, or where `width` > 0 (a camera sample's footprint, in world units) its
    // average over it by texture_filter; a procedural texture's value there
    // (core/shared/procedural_texture.h), over the same footprint.
    Rgb TextureValue(int32_t texture, const SurfacePoint& surface, float width = 0) const;
    // The material shading `surface`: its material, or where that has textures for more than
    // its base colour, a copy made in `scratch` with them applied: to its GGX alphas
    // (Material::roughness_texture), to its sheen (Material::sheen_texture, the sheen roughness
    // texture), to its transmittance (Material::transmittance_texture).
    const Material& ShadingMaterial(const SurfacePoint& surface,
                                    std::optional<Material>& scratch) const {
        const Material& material = materials[surface.material];
        if (!material.HasShadingTextures()) [[likely]]
            return material;
        return TexturedMaterial(surface, scratch);
    }
    const Material& TexturedMaterial(const SurfacePoint& surface,
                                     std::optional<Material>& scratch) const;
    // Whether material `m` (or a material a mix may be) reads texture coordinates.
    bool MaterialReadsUv(uint32_t m) const {
        if (materials[m].type != MaterialType::kMix) [[likely]]
            return materials[m].ReadsUv();
        return MixReadsUv(m);
    }
    bool MixReadsUv(uint32_t m) const;
    // Whether material `m` (or a material a mix may be) reads vertex tangents: a normal map.
    bool NeedsTangents(uint32_t m) const;
    // Diffuse reflectance or specular tint at a surface point, texture and vertex colour
    // applied (bilinear, at the point: what a photon meets).
    Rgb BaseColor(const SurfacePoint& surface) const;
    // The same averaged over a footprint `width` world units across (a camera sample's cone
    // where it meets the surface), by texture_filter (the point lookup where there is none).
    Rgb BaseColor(const SurfacePoint& surface, float width) const;
    // The radiance a surface point emits (from the sides its material emits toward), emission
    // texture applied (bilinear, at the point: what Emitters samples), and the vertex colour
    // where the material says so (gpu::kSurfaceVertexEmission).
    Rgb Emission(const SurfacePoint& surface) const;
    // The alpha of `triangle` at barycentrics (b1, b2): its material's, times its alpha
    // texture's first channel there (bilinear, at the point), times the vertex colours' alpha
    // where the material says so (gpu::kSurfaceVertexAlpha). Material::HasCutOuts says where
    // it may not be 1.
    float Alpha(uint32_t triangle, float b1, float b2) const;
    // The same of a curve at (u, v) (core/shared/curve.h).
    float CurveAlpha(uint32_t curve, float u, float v) const;
    // The area of a world triangle.
    float TriangleArea(uint32_t triangle) const;

private:
    SurfacePoint CurveSurface(const RayHit& hit) const;
    // Surface's last step where the material has a normal or bump map: `corners` are the
    // triangle's in world space.
    void AddShadingDetail(const Triangle& triangle, const Instance* instance,
                          const std::array<Vec3, 3>& corners, float b1, float b2,
                          SurfacePoint& surface) const;
};

}  // namespace pf
