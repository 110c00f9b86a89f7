// Surface reconstruction and material lookups on the world-space scene.
#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>

namespace pf {

float PunctualLight::SpotFalloff(float cos_axis) const {
    // KHR_lights_punctual, "Inner and Outer Cone Angles": a quadratic ramp between the cones.
    const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    const float t = std::clamp((cos_axis - cos_outer) * scale, 0.0f, 1.0f);
    return smooth_falloff ? t * t * (3.0f - 2.0f * t) : t * t;
}

SurfacePoint Scene::Surface(const RayHit& hit) const {
    const Triangle& triangle = triangles[hit.triangle];
    const Vec3& p0 = positions[triangle.vertex[0]];
    const Vec3& p1 = positions[triangle.vertex[1]];
    const Vec3& p2 = positions[triangle.vertex[2]];
    const float b0 = 1.0f - hit.b1 - hit.b2;
    SurfacePoint surface;
    // Barycentric interpolation is more accurate than origin + t * direction far from the origin.
    surface.position = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
    surface.geometric_normal = triangle.normal;
    surface.shading_normal = surface.geometric_normal;
    if (triangle.smooth) {
        const Vec3 n = normals[triangle.vertex[0]] * b0 + normals[triangle.vertex[1]] * hit.b1 +
                       normals[triangle.vertex[2]] * hit.b2;
        if (LengthSquared(n) > 0) surface.shading_normal = FaceForward(Normalize(n), surface.geometric_normal);
    }
    surface.material = triangle.material;
    if (materials[triangle.material].base_color_texture != kNoTexture) {  // only textures read uv
        const Point2& t0 = uvs[triangle.vertex[0]];
        const Point2& t1 = uvs[triangle.vertex[1]];
        const Point2& t2 = uvs[triangle.vertex[2]];
        surface.uv = {t0.x * b0 + t1.x * hit.b1 + t2.x * hit.b2, t0.y * b0 + t1.y * hit.b1 + t2.y * hit.b2};
        // An isotropic scale: the square root of the triangle's area in uv over its area in space.
        const float uv_area = std::abs((t1.x - t0.x) * (t2.y - t0.y) - (t2.x - t0.x) * (t1.y - t0.y));
        const float area = Length(Cross(p1 - p0, p2 - p0));
        surface.uv_per_length = area > 0 ? std::sqrt(uv_area / area) : 0.0f;
    }
    return surface;
}

Rgb Scene::BaseColor(const SurfacePoint& surface) const {
    const Material& material = materials[surface.material];
    if (material.base_color_texture == kNoTexture) return material.base_color;
    return material.base_color *
           textures[material.base_color_texture].Sample(surface.uv.x, surface.uv.y);
}

Rgb Scene::BaseColor(const SurfacePoint& surface, float width) const {
    const Material& material = materials[surface.material];
    if (material.base_color_texture == kNoTexture) return material.base_color;
    return material.base_color * textures[material.base_color_texture].SampleFiltered(
                                     surface.uv.x, surface.uv.y, width * surface.uv_per_length);
}

float Scene::TriangleArea(uint32_t triangle) const {
    const Triangle& t = triangles[triangle];
    return 0.5f * Length(Cross(positions[t.vertex[1]] - positions[t.vertex[0]],
                               positions[t.vertex[2]] - positions[t.vertex[0]]));
}

}  // namespace pf
