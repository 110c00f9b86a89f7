// Surface reconstruction and material lookups on the world-space scene.
#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>

#include "core/shared/alpha.h"
#include "core/shared/curve.h"
#include "core/shared/environment_map.h"
#include "core/shared/procedural_texture.h"
#include "core/shared/shading_normal.h"

namespace pf {

static_assert(RayHit::kCurveBit == gpu::kCurveBit, "one bit marks a curve hit on both backends");

float PunctualLight::SpotFalloff(float cos_axis) const {
    // KHR_lights_punctual, "Inner and Outer Cone Angles": a quadratic ramp between the cones.
    const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    const float t = std::clamp((cos_axis - cos_outer) * scale, 0.0f, 1.0f);
    return smooth_falloff ? t * t * (3.0f - 2.0f * t) : t * t;
}

Vec3 PunctualLight::ToLight(const Vec3& toward) const {
    const float* m = to_light.data();
    return {m[0] * toward.x + m[1] * toward.y + m[2] * toward.z,
            m[3] * toward.x + m[4] * toward.y + m[5] * toward.z,
            m[6] * toward.x + m[7] * toward.y + m[8] * toward.z};
}

Point2 PunctualLight::ProjectionExtent() const {
    const float aspect = static_cast<float>(image->width) / static_cast<float>(image->height);
    return {std::max(aspect, 1.0f) * tan_half_fov, std::max(1.0f / aspect, 1.0f) * tan_half_fov};
}

Vec3 PunctualLight::ProjectionPlanePoint(float x, float y) const {
    return gpu::ProjectionPlanePoint(ProjectionExtent(), image->width, image->height, x, y);
}

Rgb PunctualLight::ImageFactor(const Vec3& toward) const {
    if (image == nullptr) return Rgb(1.0f);
    const Vec3 local = Normalize(ToLight(toward));
    if (type == LightType::kGoniometric)
        return image->texels[gpu::EnvironmentTexel(gpu::kMappingEqualArea, image->width,
                                                   image->height, local)];
    const int32_t texel =
        gpu::ProjectionTexel(ProjectionExtent(), image->width, image->height, local);
    return texel < 0 ? Rgb(0.0f) : image->texels[static_cast<size_t>(texel)];
}

Instance Instance::Make(uint32_t prototype, const Transform& from_object) {
    Instance instance;
    instance.prototype = prototype;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column)
            instance.to_world[4 * row + column] = static_cast<float>(from_object.m[row][column]);
    const Vec3d normal_columns[3] = {from_object.ApplyNormal({1, 0, 0}),
                                     from_object.ApplyNormal({0, 1, 0}),
                                     from_object.ApplyNormal({0, 0, 1})};
    // Scaled so the largest entry is 1: the cofactors of a tiny or huge scale stay in float's
    // range.
    double largest = 0;
    for (const Vec3d& column : normal_columns)
        largest = std::max(largest, MaxComponent(Abs(column)));
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            instance.normal_map[3 * row + column] =
                static_cast<float>(normal_columns[column][row] / largest);
    return instance;
}

Bounds Curve::Box() const {
    // The control points' hull holds the curve; the band reaches half a width beyond it.
    Bounds box;
    for (const Vec3& p : control) box.Extend(p);
    box.lower = box.lower - Vec3(Radius()), box.upper = box.upper + Vec3(Radius());
    return box;
}

float Curve::Area() const {
    const float length = Length(control[1] - control[0]) + Length(control[2] - control[1]) +
                         Length(control[3] - control[2]);
    return length * 0.5f * (width[0] + width[1]);
}

Curve Scene::WorldCurve(uint32_t curve, uint32_t instance) const {
    Curve placed = curves[curve];
    if (instance == Instance::kNone) return placed;
    const Instance& by = instances[instance];
    for (Vec3& p : placed.control) p = by.ApplyPoint(p);
    for (Vec3& n : placed.normal) {
        const Vec3 mapped = by.ApplyNormal(n);
        if (LengthSquared(mapped) > 0) n = Normalize(mapped);
    }
    const float* m = by.to_world.data();
    const double determinant = double(m[0]) * (double(m[5]) * m[10] - double(m[6]) * m[9]) -
                               double(m[1]) * (double(m[4]) * m[10] - double(m[6]) * m[8]) +
                               double(m[2]) * (double(m[4]) * m[9] - double(m[5]) * m[8]);
    const auto scale = static_cast<float>(std::cbrt(std::abs(determinant)));
    for (float& w : placed.width) w *= scale;
    return placed;
}

SurfacePoint Scene::CurveSurface(const RayHit& hit) const {
    const Curve curve = WorldCurve(hit.CurveIndex(), hit.instance);
    const std::array<Vec3, 4>& p = curve.control;
    const auto type = static_cast<uint32_t>(curve.type);
    const float u = std::clamp(hit.b1, 0.0f, 1.0f);
    const float v = gpu::CurveAcross(p[0], p[1], p[2], p[3], curve.width[0], curve.width[1], type,
                                     curve.normal[0], curve.normal[1], u,
                                     hit.origin + hit.direction * hit.t, hit.direction);
    SurfacePoint surface;
    gpu::CurveSurfaceAt(p[0], p[1], p[2], p[3], curve.width[0], curve.width[1], type,
                        curve.normal[0], curve.normal[1], u, v, hit.direction, surface.position,
                        surface.geometric_normal, surface.shading_normal);
    surface.uv = {u, v};
    surface.material = ResolveMaterial(curve.material, surface.position, hit.triangle, surface.uv,
                                       surface.geometric_normal);
    return surface;
}

SurfacePoint Scene::Surface(const RayHit& hit) const {
    if (hit.IsCurve()) [[unlikely]]
        return CurveSurface(hit);
    const Triangle& triangle = triangles[hit.triangle];
    const Instance* instance = hit.instance == Instance::kNone ? nullptr : &instances[hit.instance];
    Vec3 p0 = positions[triangle.vertex[0]], p1 = positions[triangle.vertex[1]],
         p2 = positions[triangle.vertex[2]];
    if (instance)
        p0 = instance->ApplyPoint(p0), p1 = instance->ApplyPoint(p1), p2 = instance->ApplyPoint(p2);
    const float b0 = 1.0f - hit.b1 - hit.b2;
    SurfacePoint surface;
    // Barycentric interpolation is more accurate than origin + t * direction far from the origin.
    surface.position = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
    surface.geometric_normal =
        instance ? Normalize(instance->ApplyNormal(triangle.normal)) : triangle.normal;
    surface.shading_normal = surface.geometric_normal;
    if (triangle.smooth) {
        Vec3 n = normals[triangle.vertex[0]] * b0 + normals[triangle.vertex[1]] * hit.b1 +
                 normals[triangle.vertex[2]] * hit.b2;
        if (instance) n = instance->ApplyNormal(n);
        if (LengthSquared(n) > 0)
            surface.shading_normal = FaceForward(Normalize(n), surface.geometric_normal);
    }
    const bool reads_uv = MaterialReadsUv(triangle.material);
    if (reads_uv) {
        const Point2& t0 = uvs[triangle.vertex[0]];
        const Point2& t1 = uvs[triangle.vertex[1]];
        const Point2& t2 = uvs[triangle.vertex[2]];
        surface.uv = {t0.x * b0 + t1.x * hit.b1 + t2.x * hit.b2,
                      t0.y * b0 + t1.y * hit.b1 + t2.y * hit.b2};
        // An isotropic scale: the square root of the triangle's area in uv over its area in space.
        const float uv_area =
            std::abs((t1.x - t0.x) * (t2.y - t0.y) - (t2.x - t0.x) * (t1.y - t0.y));
        const float area = Length(Cross(p1 - p0, p2 - p0));
        surface.uv_per_length = area > 0 ? std::sqrt(uv_area / area) : 0.0f;
    }
    if (!colors.empty()) [[unlikely]] {
        const VertexColor &c0 = colors[triangle.vertex[0]], &c1 = colors[triangle.vertex[1]],
                          &c2 = colors[triangle.vertex[2]];
        surface.color = c0.rgb * b0 + c1.rgb * hit.b1 + c2.rgb * hit.b2;
    }
    surface.material = ResolveMaterial(triangle.material, surface.position, hit.triangle,
                                       surface.uv, surface.geometric_normal);
    // A normal or bump map reads the texture coordinates, which are set then.
    if (reads_uv && materials[surface.material].HasShadingDetail())
        AddShadingDetail(triangle, instance, {p0, p1, p2}, hit.b1, hit.b2, surface);
    return surface;
}

void Scene::AddShadingDetail(const Triangle& triangle, const Instance* instance,
                             const std::array<Vec3, 3>& corners, float b1, float b2,
                             SurfacePoint& surface) const {
    const Material& material = materials[surface.material];
    const Point2& t0 = uvs[triangle.vertex[0]];
    const Point2 duv1 = uvs[triangle.vertex[1]] - t0, duv2 = uvs[triangle.vertex[2]] - t0;
    const Vec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const float u = surface.uv.x, v = surface.uv.y;
    Vec3 n = surface.shading_normal;
    if (material.bump_texture != kNoTexture) {
        const Texture& bump = *textures[material.bump_texture];
        const Vec3 dpdu = gpu::TriangleDpDu(e1, e2, duv1, duv2);
        float d_u = 0, d_v = 0;
        if (!bump.IsProcedural()) {
            // pbrt-v4's forward differences, a texel apart.
            const float du = 1.0f / static_cast<float>(bump.width);
            const float dv = 1.0f / static_cast<float>(bump.height);
            const float d = bump.Sample(u, v).x;
            d_u = (bump.Sample(u + du, v).x - d) / du * material.bump_scale;
            d_v = (bump.Sample(u, v + dv).x - d) / dv * material.bump_scale;
        } else {
            // At the point moved along the frame's ss and ts (pbrt's v: against ours).
            const float h = gpu::kBumpStep;
            const float d = TextureValue(material.bump_texture, surface).x;
            SurfacePoint moved = surface;
            moved.position = surface.position + gpu::BumpFrameAxis(n, dpdu, 0) * h;
            moved.uv = {u + h, v};
            d_u = (TextureValue(material.bump_texture, moved).x - d) / h * material.bump_scale;
            moved.position = surface.position + gpu::BumpFrameAxis(n, dpdu, 1) * h;
            moved.uv = {u, v - h};
            d_v = -(TextureValue(material.bump_texture, moved).x - d) / h * material.bump_scale;
        }
        n = gpu::NormalFromBump(n, dpdu, d_u, d_v);
    }
    if (material.normal_texture != kNoTexture && !tangents.empty()) {
        const float b0 = 1.0f - b1 - b2;
        Vec3 tangent = tangents[triangle.vertex[0]] * b0 + tangents[triangle.vertex[1]] * b1 +
                       tangents[triangle.vertex[2]] * b2;
        if (instance) tangent = instance->ApplyVector(tangent);
        const float sign = gpu::BitangentSign(surface.geometric_normal, e1, e2, duv1, duv2);
        n = gpu::NormalFromMap(n, tangent, sign, textures[material.normal_texture]->Sample(u, v),
                               material.normal_scale);
    }
    // The shading normal stays on the front: a map tilting it past the surface is not followed.
    if (Dot(n, surface.geometric_normal) > 0) surface.shading_normal = n;
}

namespace {

// A procedural texture's images, read as the scene reads its own.
class SceneTextureImages final : public gpu::TextureImages {
public:
    explicit SceneTextureImages(const Scene& scene) : scene_(scene) {}
    gpu::vec3 ImageValue(int32_t texture, gpu::vec2 uv, float width) const override {
        if (width > 0 && scene_.texture_filter)
            return scene_.texture_filter->Sample(texture, uv.x, uv.y, width);
        return scene_.textures[texture]->Sample(uv.x, uv.y);
    }

private:
    const Scene& scene_;
};

}  // namespace

Rgb Scene::TextureValue(int32_t index, const SurfacePoint& surface, float width) const {
    const Texture& texture = *textures[index];
    if (!texture.IsProcedural()) [[likely]] {
        if (width > 0 && texture_filter)
            return texture_filter->Sample(index, surface.uv.x, surface.uv.y,
                                          width * surface.uv_per_length);
        return texture.Sample(surface.uv.x, surface.uv.y);
    }
    const gpu::TextureLookup at{surface.position, surface.geometric_normal, surface.uv, width,
                                width * surface.uv_per_length};
    return gpu::EvaluateProceduralTexture(texture.program.data(),
                                          static_cast<uint32_t>(texture.program.size()), at,
                                          SceneTextureImages(*this));
}

Rgb Scene::BaseColor(const SurfacePoint& surface) const {
    const Material& material = materials[surface.material];
    // glTF: the base colour is its factor x its texture x the vertex colour.
    const Rgb base_color = material.base_color * surface.color;
    if (material.base_color_texture == kNoTexture) return base_color;
    return base_color * TextureValue(material.base_color_texture, surface);
}

Rgb Scene::BaseColor(const SurfacePoint& surface, float width) const {
    const Material& material = materials[surface.material];
    const Rgb base_color = material.base_color * surface.color;
    if (material.base_color_texture == kNoTexture) return base_color;
    return base_color * TextureValue(material.base_color_texture, surface, width);
}

Rgb Scene::Emission(const SurfacePoint& surface) const {
    const Material& material = materials[surface.material];
    Rgb emission = material.emission;
    if ((material.surface_flags & gpu::kSurfaceVertexEmission) != 0) emission *= surface.color;
    if (material.emission_texture == kNoTexture) return emission;
    return emission * textures[material.emission_texture]->Sample(surface.uv.x, surface.uv.y);
}

uint32_t Scene::ResolveMix(uint32_t m, const Vec3& position, uint32_t triangle, const Point2& uv,
                           const Vec3& normal) const {
    // A mix's materials come before it (the loaders and the prepared scene's check see to it),
    // so this ends.
    SurfacePoint at;
    at.position = position, at.geometric_normal = normal, at.uv = uv;
    while (materials[m].type == MaterialType::kMix) {
        const Material& mix = materials[m];
        float amount = mix.mix_amount;
        if (mix.mix_texture != kNoTexture) amount *= TextureValue(mix.mix_texture, at).x;
        // Salted by the mix, so that nested mixes choose independently.
        const float u = gpu::MixHash(position, triangle * 0x9e3779b9u + m);
        m = u < amount ? mix.mix_second : mix.mix_first;
    }
    return m;
}

const Material& Scene::TexturedMaterial(const SurfacePoint& surface,
                                        std::optional<Material>& shading) const {
    Material& scratch = shading.emplace(materials[surface.material]);
    const auto sample = [&](int32_t texture) { return TextureValue(texture, surface); };
    if (scratch.roughness_texture != kNoTexture) {
        const float t = sample(scratch.roughness_texture).x;
        scratch.roughness = std::clamp(scratch.roughness * t, kMinRoughness, 1.0f);
        // A rough coat stays rough: alpha 0 would make it smooth.
        if (scratch.coat_roughness > 0)
            scratch.coat_roughness = std::clamp(scratch.coat_roughness * t, kMinRoughness, 1.0f);
    }
    if (scratch.sheen_texture != kNoTexture)
        scratch.sheen_color = Min(scratch.sheen_color * sample(scratch.sheen_texture), Rgb(1.0f));
    if (scratch.transmittance_texture != kNoTexture)
        scratch.transmittance =
            Min(scratch.transmittance * sample(scratch.transmittance_texture), Rgb(1.0f));
    if (scratch.sheen_roughness_texture != kNoTexture)
        scratch.sheen_roughness = std::clamp(
            scratch.sheen_roughness * sample(scratch.sheen_roughness_texture).x, 0.0f, 1.0f);
    return scratch;
}

bool Scene::NeedsTangents(uint32_t m) const {
    const Material& material = materials[m];
    if (material.normal_texture != kNoTexture) return true;
    return material.type == MaterialType::kMix &&
           (NeedsTangents(material.mix_first) || NeedsTangents(material.mix_second));
}

bool Scene::MixReadsUv(uint32_t m) const {
    const Material& mix = materials[m];
    return mix.ReadsUv() || MaterialReadsUv(mix.mix_first) || MaterialReadsUv(mix.mix_second);
}

float Scene::Alpha(uint32_t triangle, float b1, float b2) const {
    const Triangle& t = triangles[triangle];
    const Material& material = materials[t.material];
    float alpha = material.alpha;
    const float b0 = 1 - b1 - b2;
    if (material.alpha_texture != kNoTexture) {
        // An image (the loaders give cut-outs no procedural texture): the coordinates alone.
        SurfacePoint at;
        at.uv = {uvs[t.vertex[0]].x * b0 + uvs[t.vertex[1]].x * b1 + uvs[t.vertex[2]].x * b2,
                 uvs[t.vertex[0]].y * b0 + uvs[t.vertex[1]].y * b1 + uvs[t.vertex[2]].y * b2};
        alpha *= TextureValue(material.alpha_texture, at).x;
    }
    if ((material.surface_flags & gpu::kSurfaceVertexAlpha) != 0 && !colors.empty())
        alpha *= colors[t.vertex[0]].alpha * b0 + colors[t.vertex[1]].alpha * b1 +
                 colors[t.vertex[2]].alpha * b2;
    return alpha;
}

float Scene::CurveAlpha(uint32_t curve, float u, float v) const {
    const Material& material = materials[curves[curve].material];
    if (material.alpha_texture == kNoTexture) return material.alpha;
    return material.alpha * textures[material.alpha_texture]->Sample(u, v).x;
}

float Scene::TriangleArea(uint32_t triangle) const {
    const Triangle& t = triangles[triangle];
    return 0.5f * Length(Cross(positions[t.vertex[1]] - positions[t.vertex[0]],
                               positions[t.vertex[2]] - positions[t.vertex[0]]));
}

}  // namespace pf
