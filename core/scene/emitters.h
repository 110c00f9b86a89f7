// Every source of light in a scene (emissive triangles, punctual lights and the environment)
// behind one interface: emitting photons in proportion to power, and sampling direct light at
// a point.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/ray.h"
#include "core/math/vec3.h"
#include "core/sampling/distribution.h"
#include "core/sampling/frame.h"
#include "core/sampling/rng.h"
#include "core/scene/environment.h"
#include "core/scene/scene.h"
#include "core/shared/photon_chain.h"

namespace pf {

// The most power a scene's lights may emit in all, W: every photon carries the total power,
// and a batch sums up to 2^26 of them, several times over for long paths, in float (3.4e38),
// so 2^-36 of float's range leaves room for 2^10 deposits per photon on average.
inline constexpr double kMaxLightPower = 0x1p-36 * 3.4028234663852886e38;

struct EmittedPhoton {
    Ray ray;   // origin already offset from the emitting surface
    Rgb flux;  // W: this photon's share of the scene's power times N_emitted (divide by it)
    // The light's range (PunctualLight::range): the flux is still to be multiplied by its
    // window at the photon's first hit. 0: none.
    const PunctualLight* ranged = nullptr;
};

struct LightSample {
    Ray shadow_ray;         // from the receiver toward the light, t_max short of it
    Vec3 direction;         // unit, receiver to light
    Rgb radiance_over_pdf;  // incident radiance / pdf(solid angle), cosine at the receiver excluded
    // The sample's density in solid angle at the receiver, the emitter's pick included, for
    // multiple importance sampling; 0 for a punctual light (a delta, which only light
    // sampling can find).
    float pdf = 0;
};

enum class EmitterKind : uint32_t { kTriangle, kPunctual, kEnvironment };

// The numbers a photon's emission takes, all drawn before its walk: the emitter's pick, then
// the point and direction (a triangle takes all six; lights.glsl the same). The chains of
// adaptive photon tracing mutate them (core/shared/photon_chain.h).
struct EmissionNumbers {
    std::array<float, gpu::kEmissionNumbers> u{};

    static EmissionNumbers Draw(Rng& rng) {
        EmissionNumbers numbers;
        for (float& u : numbers.u) u = rng.NextFloat();
        return numbers;
    }
};

class Emitters {
public:
    // The scene must outlive this object. Throws nothing; a scene without light has no
    // emitters (HasPower() false) and must be refused before rendering.
    explicit Emitters(const Scene& scene);

    bool HasPower() const { return total_power_ > 0; }
    // Total emitted power, W per RGB channel.
    Rgbd TotalPower() const { return power_rgb_; }

    EmittedPhoton Emit(const EmissionNumbers& numbers) const;
    EmittedPhoton Emit(Rng& rng) const { return Emit(EmissionNumbers::Draw(rng)); }
    // One light sample for direct lighting at receiver point p with facing normal n.
    // Returns false when the sample carries no light (behind the light, outside a spot cone).
    bool SampleDirect(const Vec3& p, const Vec3& n, Rng& rng, LightSample* sample) const;
    // The same from given numbers: `pick` chooses the emitter, `u` the point on it; with
    // `pick_from_u`, u.x chooses the emitter and is then rescaled within the emitter's share
    // (DiscreteDistribution::Remap), so that stratified u spread over all emitters together.
    bool SampleDirect(const Vec3& p, const Vec3& n, float pick, Point2 u, LightSample* sample,
                      bool pick_from_u = false) const;
    // The density in solid angle with which SampleDirect, at receiver point p, picks the point
    // `on_light` of world triangle `triangle` (0 if the triangle emits nothing): for weighing
    // a path that found the light by scattering against light sampling (Veach 1997, ch. 9).
    float PdfDirect(uint32_t triangle, const Vec3& p, const Vec3& on_light) const;
    // What a ray from p finds where it hits point `on_light` of a world triangle (`hit`: the
    // triangle and the point's barycentrics): the radiance emitted toward p, and PdfDirect's
    // density. Both 0 where the triangle emits nothing, or not toward p.
    struct Hit {
        Rgb radiance;
        float pdf = 0;
    };
    Hit HitEmitter(const RayHit& hit, const Vec3& p, const Vec3& on_light) const;
    // What a ray from `origin` that escapes the scene toward unit direction `toward` finds:
    // the environment's radiance, and the density in solid angle with which SampleDirect at
    // `origin` picks that direction. Both 0 without an environment, or where its portal does
    // not let the ray out.
    Hit Escaped(const Vec3& origin, const Vec3& toward) const;
    // Whether any emitter is a triangle, which a ray can hit (punctual lights only light
    // sampling finds).
    bool HasTriangles() const { return !triangles_.empty(); }
    bool HasEnvironment() const { return environment_emitter_ >= 0; }
    // Whether a ray can find light: a triangle it hits or an environment it escapes to.
    bool FoundByRays() const { return HasTriangles() || HasEnvironment(); }
    // The index into Records() of world triangle `triangle`'s emitter, or -1.
    int32_t EmitterOfTriangle(uint32_t triangle) const {
        return triangle < emitter_of_triangle_.size() ? emitter_of_triangle_[triangle] : -1;
    }

    // Each emitter as another backend needs it to emit and sample the same light (the Vulkan
    // backend uploads these), in selection order.
    struct Record {
        EmitterKind kind = EmitterKind::kTriangle;
        uint32_t light = 0;             // punctual: index into Scene::lights
        Vec3 p0, edge1, edge2, normal;  // triangle: corners and unit emitting normal
        Rgb radiance;                   // triangle: Le (times the texel, with a texture)
        float area = 0;                 // triangle
        bool two_sided = false;         // triangle: emits from its back face too
        bool invisible = false;         // triangle: cut out everywhere (EmissiveTriangle's)
        // Triangle: the emission texture (index into Scene::textures) or kNoTexture, and the
        // texture coordinates at p0 and along the edges.
        int32_t texture = kNoTexture;
        Point2 uv0, uv_edge1, uv_edge2;
        // Triangle: the world triangle whose vertex colours scale its emission (glTF's unlit
        // base colour, gpu::kSurfaceVertexEmission), or -1.
        int32_t colored_triangle = -1;
        // W per channel: a photon's flux before the 1 / probability of its pick (and before
        // the texel and vertex colour it leaves from for a textured or coloured triangle, and
        // the falloff of its direction for a spot light).
        Rgb power;
        // The largest factor of `power` per channel a photon's texel or falloff may bring.
        float peak = 1;
        double probability = 0;  // of being picked by Emit and SampleDirect
    };
    std::vector<Record> Records() const;
    // The environment's direction sampling (its tables for upload); HasEnvironment() only.
    const EnvironmentSampler& EnvironmentSampling() const { return environment_sampler_; }
    // With a portal, the photons' directions: over the hemisphere outside it, by the cosine.
    const EnvironmentSampler& PortalSampling() const { return portal_sampler_; }
    // The directions of a goniometric or projection light, drawn in proportion to its
    // intensity: a goniometric light's map as an environment's (its texels span equal solid
    // angles); a projection's texels by value x the solid angle each spans, then a point
    // uniform on the image plane within the texel.
    struct ImageSampler {
        // Goniometric: the intensity over the sphere (held apart: `directions` points to it).
        std::shared_ptr<const Environment> environment;
        EnvironmentSampler directions;
        DiscreteDistribution texels;  // projection
        float plane_texel_area = 0;   // projection: a texel's area on the plane z = 1
        Rgbd power;                   // the light's power, W per channel
    };
    // A goniometric or projection light's sampling (its tables for upload), by its index
    // into Scene::lights.
    const ImageSampler& ImageSampling(uint32_t light) const { return image_samplers_[light]; }
    // The bounding sphere directional lights emit across.
    Vec3 SceneCenter() const { return scene_center_; }
    // The scene's largest coordinate magnitude, which ray origins are offset by (OffsetRayOrigin).
    float SceneScale() const { return scene_.bounds.Magnitude(); }
    float SceneRadius() const { return scene_radius_; }

private:
    struct Emitter {
        EmitterKind kind;
        uint32_t index;  // into triangles_ or Scene::lights (0 for the environment)
        Rgb power;       // W per channel
    };
    // An emissive triangle, with what sampling it needs precomputed.
    struct EmissiveTriangle {
        Vec3 p0, edge1, edge2;
        Frame frame;   // around the unit normal of the emitting side
        Rgb radiance;  // Le, times the texel where there is a texture
        float area;
        bool two_sided;                    // emits from the back face too
        const Texture* texture = nullptr;  // the emission texture, if any
        int32_t texture_index = kNoTexture;
        Point2 uv0, uv_edge1, uv_edge2;  // texture coordinates, where there is one
        // Cut out everywhere (alpha 0): no ray meets it, so light sampling alone finds its
        // light, unweighed by MIS (pbrt-v4's invisible area lights, taken as delta lights).
        bool invisible = false;
        // The vertex colours scaling Le, interpolated (Scene::colors), where `colored`; and
        // the world triangle they are of.
        bool colored = false;
        std::array<Rgb, 3> colors{Rgb(1.0f), Rgb(1.0f), Rgb(1.0f)};
        uint32_t triangle = 0;
        // What scales Le at barycentrics (b1, b2): the vertex colour times the texel.
        Rgb FactorAt(float b1, float b2) const {
            Rgb factor(1.0f);
            if (colored) factor = colors[0] * (1 - b1 - b2) + colors[1] * b1 + colors[2] * b2;
            if (texture != nullptr)
                factor *= texture->Sample(uv0.x + uv_edge1.x * b1 + uv_edge2.x * b2,
                                          uv0.y + uv_edge1.y * b1 + uv_edge2.y * b2);
            return factor;
        }
        // Le at barycentrics (b1, b2).
        Rgb RadianceAt(float b1, float b2) const {
            if (texture == nullptr && !colored) return radiance;
            return radiance * FactorAt(b1, b2);
        }
        // Emitted power, W per channel: pi A Le from each emitting side, the texture and
        // vertex colours integrated over the triangle.
        Rgbd Power() const;
        // The cosine at the light toward `to_light` (unit, from the receiver): of the side that
        // faces the receiver for a two-sided light.
        float CosineToward(const Vec3& to_light) const {
            const float cosine = -Dot(frame.n, to_light);
            return two_sided ? std::abs(cosine) : cosine;
        }
    };
    static ImageSampler MakeImageSampler(const PunctualLight& light);
    // Each from the numbers after the pick (EmissionNumbers::u + 1): a triangle takes five,
    // the others at most four.
    EmittedPhoton EmitFromTriangle(const EmissiveTriangle& triangle, const float* u) const;
    EmittedPhoton EmitFromLight(const PunctualLight& light, uint32_t index, const float* u) const;
    EmittedPhoton EmitFromImageLight(const PunctualLight& light, const ImageSampler& sampler,
                                     const float* u) const;
    EmittedPhoton EmitFromEnvironment(const float* u) const;

    const Scene& scene_;
    std::vector<Emitter> emitters_;
    std::vector<EmissiveTriangle> triangles_;
    DiscreteDistribution distribution_;       // over emitters_, by power
    std::vector<float> inverse_probability_;  // 1 / selection probability, per emitter
    // Per world triangle, its index into emitters_, or -1 where it emits nothing.
    std::vector<int32_t> emitter_of_triangle_;
    EnvironmentSampler environment_sampler_;
    EnvironmentSampler portal_sampler_;         // with a portal only
    std::vector<ImageSampler> image_samplers_;  // per Scene::lights entry; empty for most
    int32_t environment_emitter_ = -1;          // its index into emitters_
    Rgbd power_rgb_;
    double total_power_ = 0;
    Vec3 scene_center_;
    float scene_radius_ = 0;
};

}  // namespace pf
