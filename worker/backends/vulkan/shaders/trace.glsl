// Ray queries against the scene's BVH (built on the CPU by Embree's builder, flattened to
// GpuBvhNode): closest hit and any hit, a stack-based traversal visiting the nearer child
// first, Moeller-Trumbore triangle tests and pbrt-v4's curve test (core/shared/curve.h),
// cut-outs passed through.
struct RayHit {
    float t;
    uint triangle;    // in leaf order (the triangles binding): a triangle's slot or a curve's
    float b1, b2;     // barycentrics of vertices 1 and 2; a curve's u and v
    vec3 direction;   // the ray's, unit (a curve faces it)
};

// Entry distance of the ray into the box, or infinity where it misses within (0, t_max).
float EnterBox(vec3 lower, vec3 upper, vec3 origin, vec3 inverse_direction, float t_max) {
    const vec3 t0 = (lower - origin) * inverse_direction, t1 = (upper - origin) * inverse_direction;
    const vec3 near = min(t0, t1), far = max(t0, t1);
    const float enter = max(max(near.x, near.y), max(near.z, 0.0));
    const float leave = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= leave ? enter : kInfinity;
}

// Texel (x, y) of `texture`, wrapped as it says; black where it says so beyond the image.
vec3 TextureTexel(GpuTexture texture, int x, int y) {
    WrapTexels(x, y, texture.width, texture.height, texture.wrap & 0xffffu, texture.wrap >> 16);
    if (x < 0 || y < 0) return vec3(0.0);
    return texels[texture.first_texel + uint(y * texture.width + x)].xyz;
}

vec3 TextureSample(GpuTexture texture, vec2 uv) {
    // Bilinear at glTF coordinates, as core/scene/texture.h.
    const vec2 xy = uv * vec2(texture.width, texture.height) - 0.5;
    const vec2 floor_xy = floor(xy);
    const vec2 w = xy - floor_xy;
    const ivec2 p0 = ivec2(floor_xy);
    const vec3 top = mix(TextureTexel(texture, p0.x, p0.y), TextureTexel(texture, p0.x + 1, p0.y), w.x);
    const vec3 bottom = mix(TextureTexel(texture, p0.x, p0.y + 1), TextureTexel(texture, p0.x + 1, p0.y + 1), w.x);
    return mix(top, bottom, w.y);
}

// Where vertex v's tangent and colour lie in the tangents binding (gpu::kBindingTangents).
uint TangentSlot(uint v) { return kHasVertexColors ? 2u * v : v; }
uint ColorSlot(uint v) { return kHasShadingDetail ? 2u * v + 1u : v; }

// The vertex colours (rgb, alpha) of `vertices` interpolated at barycentrics (b1, b2)
// (Scene::colors); only where the scene has them.
vec4 VertexColorAt(uvec3 vertices, float b1, float b2) {
    return vertex_tangents[ColorSlot(vertices.x)] * (1.0 - b1 - b2) + vertex_tangents[ColorSlot(vertices.y)] * b1 +
           vertex_tangents[ColorSlot(vertices.z)] * b2;
}

// A procedural texture's image operands (core/shared/procedural_texture.h), at the point.
vec3 ProceduralImage(int texture, vec2 uv) { return TextureSample(textures[texture], uv); }

#include "core/shared/procedural_texture.h"

// Texture `texture` at a surface point: an image's texel at its coordinates, or a procedural
// texture there (Scene::TextureValue's point lookup).
vec3 TextureValue(int texture, vec3 position, vec3 normal, vec2 uv) {
    const GpuTexture image = textures[texture];
    if (!kHasProceduralTextures || image.width > 0) return TextureSample(image, uv);
    return EvaluateProceduralTexture(image.first_texel, uint(image.height),
                                     TextureLookup(position, normal, uv, 0.0, 0.0), 0u);
}

// Whether the ray meets scene triangle `index` at (b1, b2) or passes through a cut-out there, or
// through a single-sided surface's back face, as the CPU tracer's Embree filter decides
// (core/shared/alpha.h, Scene::Alpha).
bool MeetsSurface(uint index, float b1, float b2, vec3 origin, vec3 direction) {
    const GpuTriangleShading shade = shading[index];
    const GpuMaterial material = materials[shade.vertices.w & ~kSmoothBit];
    const uint flags = floatBitsToUint(material.alpha.w);
    if (PassesBackFace(flags, dot(direction, shade.normal.xyz))) return false;
    float alpha = material.alpha.x;
    const int texture = floatBitsToInt(material.alpha.z);
    const bool vertex_alpha = kHasVertexColors && (flags & kSurfaceVertexAlpha) != 0;
    if (alpha >= 1.0 && texture < 0 && !vertex_alpha) return true;
    if (texture >= 0) {
        const vec2 uv = vertex_uvs[shade.vertices.x] * (1.0 - b1 - b2) + vertex_uvs[shade.vertices.y] * b1 +
                        vertex_uvs[shade.vertices.z] * b2;
        alpha *= TextureSample(textures[texture], uv).x;  // the loaders give cut-outs images
    }
    if (vertex_alpha) alpha *= VertexColorAt(shade.vertices.xyz, b1, b2).w;
    if (alpha >= 1.0) return true;
    return AlphaMeets(alpha, material.alpha.y, AlphaHash(origin, direction, index));
}

// A curve's two records (GpuTriangle's comment), from the first.
struct CurveRecord {
    vec3 p0, p1, p2, p3;  // Bezier control points
    float w0, w1;         // widths at its ends
    vec3 n0, n1;          // a ribbon's end normals
    uint material, type, index;
};

CurveRecord LoadCurve(uint record) {
    const GpuTriangle a = triangles[record], b = triangles[record + 1u];
    return CurveRecord(a.p0.xyz, a.edge1.xyz, a.edge2.xyz, b.p0.xyz, a.p0.w, a.edge1.w, b.edge1.xyz, b.edge2.xyz,
                       floatBitsToUint(a.edge2.w), floatBitsToUint(b.p0.w), floatBitsToUint(b.edge1.w));
}

// The curve record a leaf slot names, or kCurveBit's complement where the slot is a triangle's.
uint CurveOfSlot(uint slot) {
    if (!kHasCurves) return ~kCurveBit;
    const uint bits = floatBitsToUint(triangles[slot].p0.w);
    return (bits & kCurveBit) != 0u ? bits & ~kCurveBit : ~kCurveBit;
}

// Whether the ray meets the curve at (u, v) or passes through a cut-out there (Scene::CurveAlpha,
// the CPU tracer's curve filter).
bool MeetsCurve(CurveRecord curve, float u, float v, vec3 origin, vec3 direction) {
    const GpuMaterial material = materials[curve.material];
    float alpha = material.alpha.x;
    const int texture = floatBitsToInt(material.alpha.z);
    if (alpha >= 1.0 && texture < 0) return true;
    if (texture >= 0) alpha *= TextureSample(textures[texture], vec2(u, v)).x;
    return AlphaMeets(alpha, material.alpha.y, AlphaHash(origin, direction, kCurveBit | curve.index));
}

bool IntersectCurveSlot(uint slot, uint record, vec3 origin, vec3 direction, inout float t_max, inout RayHit hit) {
    const CurveRecord c = LoadCurve(record);
    float t, u, v;
    if (!IntersectCurve(origin, direction, t_max, c.p0, c.p1, c.p2, c.p3, c.w0, c.w1, c.type, c.n0, c.n1, t, u, v))
        return false;
    if (kHasCutOuts && !MeetsCurve(c, u, v, origin, direction)) return false;
    t_max = t;
    hit = RayHit(t, slot, u, v, direction);
    return true;
}

bool IntersectTriangle(uint index, vec3 origin, vec3 direction, inout float t_max, inout RayHit hit) {
    const GpuTriangle triangle = triangles[index];
    const vec3 p = cross(direction, triangle.edge2.xyz);
    const float determinant = dot(triangle.edge1.xyz, p);
    if (determinant == 0) return false;
    const float inverse = 1.0 / determinant;
    const vec3 to_origin = origin - triangle.p0.xyz;
    const float b1 = dot(to_origin, p) * inverse;
    if (b1 < 0 || b1 > 1) return false;
    const vec3 q = cross(to_origin, triangle.edge1.xyz);
    const float b2 = dot(direction, q) * inverse;
    if (b2 < 0 || b1 + b2 > 1) return false;
    const float t = dot(triangle.edge2.xyz, q) * inverse;
    if (!(t > 0 && t < t_max)) return false;
    // Only the triangles whose material has cut-outs pay for the test.
    if (kHasCutOuts && triangle.edge1.w != 0.0 && !MeetsSurface(floatBitsToUint(triangle.p0.w), b1, b2, origin, direction))
        return false;
    t_max = t;
    hit = RayHit(t, index, b1, b2, direction);
    return true;
}

bool IntersectPrimitive(uint slot, vec3 origin, vec3 direction, inout float t_max, inout RayHit hit) {
    const uint curve = CurveOfSlot(slot);
    if (kHasCurves && curve != ~kCurveBit) return IntersectCurveSlot(slot, curve, origin, direction, t_max, hit);
    return IntersectTriangle(slot, origin, direction, t_max, hit);
}

// Closest hit along origin + t direction, 0 < t < t_max; with `any_hit`, the first found.
bool TraceRay(vec3 origin, vec3 direction, float t_max, bool any_hit, out RayHit hit) {
    hit = RayHit(0, 0, 0, 0, direction);
    // Zero components become tiny ones, so the slab test never computes 0 x infinity.
    const vec3 safe = mix(vec3(1e-30), direction, greaterThan(abs(direction), vec3(1e-30)));
    const vec3 inverse_direction = 1.0 / safe;
    uint stack[kBvhStackSize];  // core/shared/gpu_types.h: the builder's depth limit
    uint depth = 0;
    uint node = 0;
    bool found = false;
    while (true) {
        const GpuBvhNode n = bvh_nodes[node];
        const float enter_left = EnterBox(n.left_lower.xyz, n.left_upper.xyz, origin, inverse_direction, t_max);
        const float enter_right = EnterBox(n.right_lower.xyz, n.right_upper.xyz, origin, inverse_direction, t_max);
        const uint left = floatBitsToUint(n.left_lower.w), left_count = floatBitsToUint(n.left_upper.w);
        const uint right = floatBitsToUint(n.right_lower.w), right_count = floatBitsToUint(n.right_upper.w);
        bool visit_left = enter_left < kInfinity, visit_right = enter_right < kInfinity;
        if (visit_left && left_count > 0) {
            for (uint i = left; i < left + left_count; ++i) found = IntersectPrimitive(i, origin, direction, t_max, hit) || found;
            visit_left = false;
        }
        if (visit_right && right_count > 0) {
            for (uint i = right; i < right + right_count; ++i) found = IntersectPrimitive(i, origin, direction, t_max, hit) || found;
            visit_right = false;
        }
        if (found && any_hit) return true;
        if (visit_left && visit_right) {
            const bool left_first = enter_left <= enter_right;
            stack[depth++] = left_first ? right : left;
            node = left_first ? left : right;
        } else if (visit_left || visit_right) {
            node = visit_left ? left : right;
        } else {
            if (depth == 0) break;
            node = stack[--depth];
        }
    }
    return found;
}

// A surface point rebuilt from a hit, as Scene::Surface does.
struct Surface {
    vec3 position;
    vec3 geometric_normal;  // the winding's front
    vec3 shading_normal;    // on the same side
    uint material;
    vec3 base_color;        // reflectance or tint, texture applied
    vec2 uv;                // texture coordinates, where the scene has textures that need them
};

// The normal and bump maps' change to the shading normal, as Scene::AddShadingDetail makes it.
void AddShadingDetail(GpuMaterial material, GpuTriangle triangle, GpuTriangleShading shade, RayHit hit,
                      inout Surface surface) {
    const int normal_texture = floatBitsToInt(material.detail.x), bump_texture = floatBitsToInt(material.detail.z);
    if (normal_texture < 0 && bump_texture < 0) return;
    const vec2 t0 = vertex_uvs[shade.vertices.x];
    const vec2 duv1 = vertex_uvs[shade.vertices.y] - t0, duv2 = vertex_uvs[shade.vertices.z] - t0;
    vec3 n = surface.shading_normal;
    if (bump_texture >= 0) {
        const GpuTexture bump = textures[bump_texture];
        const vec3 dpdu = TriangleDpDu(triangle.edge1.xyz, triangle.edge2.xyz, duv1, duv2);
        float d_u, d_v;
        if (!kHasProceduralTextures || bump.width > 0) {
            const float du = 1.0 / float(bump.width), dv = 1.0 / float(bump.height);
            const float d = TextureSample(bump, surface.uv).x;
            d_u = (TextureSample(bump, surface.uv + vec2(du, 0.0)).x - d) / du * material.detail.w;
            d_v = (TextureSample(bump, surface.uv + vec2(0.0, dv)).x - d) / dv * material.detail.w;
        } else {  // as Scene::AddShadingDetail: at the point and moved along ss and ts, one lookup
            float d[3];
            for (int i = 0; i < 3; ++i) {
                const vec3 moved = i == 0 ? vec3(0.0) : BumpFrameAxis(n, dpdu, i - 1) * kBumpStep;
                const vec2 uv = surface.uv + (i == 0 ? vec2(0.0) : (i == 1 ? vec2(kBumpStep, 0.0) : vec2(0.0, -kBumpStep)));
                d[i] = TextureValue(bump_texture, surface.position + moved, surface.geometric_normal, uv).x;
            }
            d_u = (d[1] - d[0]) / kBumpStep * material.detail.w;
            d_v = -(d[2] - d[0]) / kBumpStep * material.detail.w;
        }
        n = NormalFromBump(n, dpdu, d_u, d_v);
    }
    if (normal_texture >= 0) {
        const float b0 = 1.0 - hit.b1 - hit.b2;
        const vec3 tangent = vertex_tangents[TangentSlot(shade.vertices.x)].xyz * b0 +
                             vertex_tangents[TangentSlot(shade.vertices.y)].xyz * hit.b1 +
                             vertex_tangents[TangentSlot(shade.vertices.z)].xyz * hit.b2;
        const float sign =
            BitangentSign(surface.geometric_normal, triangle.edge1.xyz, triangle.edge2.xyz, duv1, duv2);
        n = NormalFromMap(n, tangent, sign, TextureSample(textures[normal_texture], surface.uv), material.detail.y);
    }
    if (dot(n, surface.geometric_normal) > 0.0) surface.shading_normal = n;
}

// The material of the triangle or curve in leaf slot `slot`, before a mix's choice.
uint SlotMaterial(uint slot) {
    const uint curve = CurveOfSlot(slot);
    if (kHasCurves && curve != ~kCurveBit) return floatBitsToUint(triangles[curve].edge2.w);
    return shading[floatBitsToUint(triangles[slot].p0.w)].vertices.w & ~kSmoothBit;
}

Surface SurfaceAt(RayHit hit) {
    Surface surface;
    GpuTriangle triangle;
    GpuTriangleShading shade;
    uint salt;  // the mix's hash's: the scene triangle's index, or kCurveBit | the curve's
    const uint curve = CurveOfSlot(hit.triangle);
    const bool on_curve = kHasCurves && curve != ~kCurveBit;
    if (on_curve) {  // Scene::CurveSurface
        const CurveRecord c = LoadCurve(curve);
        CurveSurfaceAt(c.p0, c.p1, c.p2, c.p3, c.w0, c.w1, c.type, c.n0, c.n1, hit.b1, hit.b2, hit.direction,
                       surface.position, surface.geometric_normal, surface.shading_normal);
        surface.uv = vec2(hit.b1, hit.b2);
        surface.material = c.material;
        salt = kCurveBit | c.index;
    } else {
        triangle = triangles[hit.triangle];
        shade = shading[floatBitsToUint(triangle.p0.w)];
        surface.position = triangle.p0.xyz + triangle.edge1.xyz * hit.b1 + triangle.edge2.xyz * hit.b2;
        surface.geometric_normal = shade.normal.xyz;
        surface.shading_normal = shade.normal.xyz;
        surface.material = shade.vertices.w & ~kSmoothBit;
        const float b0 = 1.0 - hit.b1 - hit.b2;
        surface.uv = vec2(0);
        if (kHasTextures || kHasRoughnessTextures || kHasMixTextures || kHasShadingDetail)
            surface.uv = vertex_uvs[shade.vertices.x] * b0 + vertex_uvs[shade.vertices.y] * hit.b1 +
                         vertex_uvs[shade.vertices.z] * hit.b2;
        salt = floatBitsToUint(triangle.p0.w);
    }
    // One of a mix's materials at this point, as Scene::ResolveMaterial picks, then its base
    // colour: a texture lookup a step (the kernels inline every call: one copy of a procedural
    // texture's evaluation).
    for (uint m = surface.material;; m = surface.material) {
        const bool mix = kHasMixes && materials[m].type == kMaterialMix;
        const int texture = mix ? (kHasMixTextures ? int(materials[m].mix.w) : -1) : (kHasTextures ? materials[m].texture : -1);
        const vec3 value =
            texture >= 0 ? TextureValue(texture, surface.position, surface.geometric_normal, surface.uv) : vec3(1.0);
        if (!mix) {
            surface.base_color = materials[m].base_color.xyz * value;
            break;
        }
        const float amount = uintBitsToFloat(materials[m].mix.z) * value.x;
        const float u = MixHash(surface.position, salt * 0x9e3779b9u + m);
        surface.material = u < amount ? materials[m].mix.y : materials[m].mix.x;
    }
    if (on_curve) return surface;  // no vertex normals, maps or colours
    const float b0 = 1.0 - hit.b1 - hit.b2;
    if (kHasSmoothNormals && (shade.vertices.w & kSmoothBit) != 0) {
        const vec3 n = vertex_normals[shade.vertices.x].xyz * b0 + vertex_normals[shade.vertices.y].xyz * hit.b1 +
                       vertex_normals[shade.vertices.z].xyz * hit.b2;
        if (dot(n, n) > 0) surface.shading_normal = dot(n, surface.geometric_normal) < 0 ? -normalize(n) : normalize(n);
    }
    const GpuMaterial material = materials[surface.material];
    if (kHasShadingDetail) AddShadingDetail(material, triangle, shade, hit, surface);
    // glTF's base colour: factor x vertex colour x texture (Scene::BaseColor).
    if (kHasVertexColors) surface.base_color *= VertexColorAt(shade.vertices.xyz, hit.b1, hit.b2).xyz;
    return surface;
}

vec3 SurfaceTexture(int texture, Surface surface) {
    return TextureValue(texture, surface.position, surface.geometric_normal, surface.uv);
}

// The material shading a surface point, its roughness, sheen and transmittance textures applied
// (Scene::ShadingMaterial).
GpuMaterial ShadingMaterial(Surface surface) {
    GpuMaterial material = materials[surface.material];
    // Each texture in turn through one lookup (the kernels inline every call: one copy of a
    // procedural texture's evaluation): roughness, transmittance, sheen colour and roughness.
    for (int slot = 0; slot < 4; ++slot) {
        int texture = -1;
        if (slot == 0 && kHasRoughnessTextures) texture = material.roughness_texture;
        if (slot == 1 && kHasTranslucency && kHasTextures) texture = floatBitsToInt(material.transmittance.w);
        if (slot == 2 && kHasSheen) texture = floatBitsToInt(material.layer.z);
        if (slot == 3 && kHasSheen) texture = floatBitsToInt(material.layer.w);
        if (texture < 0) continue;
        const vec3 value = SurfaceTexture(texture, surface);
        if (slot == 0) {
            material.roughness = clamp(material.roughness * value.x, 1e-3, 1.0);
            if (material.coat.y > 0.0) material.coat.y = clamp(material.coat.y * value.x, 1e-3, 1.0);
        } else if (slot == 1) {
            material.transmittance.xyz = min(material.transmittance.xyz * value, vec3(1.0));
        } else if (slot == 2) {
            material.sheen.xyz = min(material.sheen.xyz * value, vec3(1.0));
        } else {
            material.sheen.w = clamp(material.sheen.w * value.x, 0.0, 1.0);
        }
    }
    return material;
}

// Moves p off the surface along n (OffsetRayOrigin in core/geometry/ray.h).
vec3 OffsetRayOrigin(vec3 p, vec3 n) {
    const float scale = params.scene_magnitude;
    return vec3(OffsetCoordinate(p.x, n.x, scale), OffsetCoordinate(p.y, n.y, scale), OffsetCoordinate(p.z, n.z, scale));
}
