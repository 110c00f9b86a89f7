// Photon emission and light sampling over the scene's emitters, as core/scene/emitters.cpp
// does on the CPU, with the shared warps (core/shared/path_sampling.h) and consuming random
// numbers in the same order; light kinds the scene lacks are compiled out.
#include "environment.glsl"

// The spot's falloff, glTF's quadratic or pbrt's smoothstep (PunctualLight::SpotFalloff).
float SpotFalloff(GpuEmitter light, float cos_axis) {
    const float t = clamp((cos_axis - light.cone.y) * light.cone.z, 0.0, 1.0);
    return light.cone.w != 0.0 ? t * t * (3.0 - 2.0 * t) : t * t;
}

uint EmitterKind(GpuEmitter emitter) { return floatBitsToUint(emitter.position.w); }

// What scales a triangle light's radiance at barycentrics b: its vertex colour times its
// emission texture's texel, 1 where it has neither (Emitters::EmissiveTriangle::FactorAt).
vec3 EmissionTexel(GpuEmitter emitter, vec2 b) {
    vec3 factor = vec3(1);
    if (kHasVertexColors) {
        const uint triangle = floatBitsToUint(emitter.texture.w);
        if (triangle != kNoEmitter) factor = VertexColorAt(shading[triangle].vertices.xyz, b.x, b.y).xyz;
    }
    const int texture = floatBitsToInt(emitter.texture.z);
    if (kHasTexturedLights && texture >= 0)
        factor *= TextureSample(textures[texture],
                                emitter.texture.xy + emitter.uv_edges.xy * b.x + emitter.uv_edges.zw * b.y);
    return factor;
}

// The cosine at a triangle light toward unit to_light (from the receiver): of the side that
// faces the receiver for a two-sided light.
float CosineToward(GpuEmitter emitter, vec3 to_light) {
    const float cosine = -dot(emitter.direction.xyz, to_light);
    return emitter.direction.w != 0.0 ? abs(cosine) : cosine;
}

// A projection light's image (Emitters::ImageSampler): where its texels' tables begin, the
// intensity toward unit world direction `toward` (PunctualLight::ImageFactor, the light's
// intensity included), and a direction drawn by the texels' share of the power, uniform on
// the image plane within the texel.
uint ProjectionProbabilityBegin(GpuEmitter e) {
    return FirstTableEntry(e) + uint(EnvironmentWidth(e) * EnvironmentHeight(e)) + 1u;
}

vec3 ProjectionIntensity(GpuEmitter e, vec3 toward) {
    const int texel = ProjectionTexel(e.texture.zw, EnvironmentWidth(e), EnvironmentHeight(e),
                                      EnvironmentToMap(e, toward));
    if (texel < 0) return vec3(0);
    return light_image_texels[FirstTexel(e) + uint(texel)].xyz * e.radiance.xyz;
}

// Emitters::EmitFromImageLight: the photon's direction and flux (before its pick).
void ProjectionEmit(GpuEmitter e, float u1, float u2, float u3, out vec3 toward,
                    out vec3 flux) {
    const int width = EnvironmentWidth(e), height = EnvironmentHeight(e);
    float unused;
    const uint texel = FindEnvironmentInterval(FirstTableEntry(e), uint(width * height), u1, unused);
    const uint x = texel % uint(width), y = texel / uint(width);
    const vec3 local = normalize(
        ProjectionPlanePoint(e.texture.zw, width, height, float(x) + u2, float(y) + u3));
    toward = EnvironmentToWorld(e, local);
    // The density in solid angle: the texel's probability over its plane area, times the
    // plane's dA / d(omega) = 1 / cos^3.
    const float pdf = light_image_tables[ProjectionProbabilityBegin(e) + texel] / e.edge1.w /
                      (local.z * local.z * local.z);
    flux = pdf > 0 ? light_image_texels[FirstTexel(e) + texel].xyz * e.radiance.xyz / pdf
                   : vec3(0);
}

// Picks an emitter in proportion to its power by inverting the CDF.
uint PickEmitter(float u) {
    uint low = 0, high = params.emitter_count - 1;
    while (low < high) {
        const uint middle = (low + high) / 2;
        if (u < emitter_cdf[middle]) high = middle; else low = middle + 1;
    }
    return low;
}

struct Photon {
    vec3 origin, direction;
    vec3 flux;    // W x photons emitted
    float range;  // the light's range, whose window the flux still takes at the first hit
};

// From the numbers drawn before the photon's walk (kEmissionNumbers, core/shared/photon_chain.h):
// the pick, then the point and direction, in Emitters::Emit's order.
Photon EmitPhotonFrom(const float u[kEmissionNumbers]) {
    const GpuEmitter emitter = emitters[PickEmitter(u[0])];
    const uint kind = EmitterKind(emitter);
    Photon photon;
    photon.flux = emitter.power.xyz * emitter.power.w;
    photon.range = 0;
    if (kHasTriangleLights && kind == kEmitterTriangle) {
        const vec2 b = SampleUniformTriangle(u[1], u[2]);
        const vec3 point = emitter.position.xyz + emitter.edge1.xyz * b.x + emitter.edge2.xyz * b.y;
        // A two-sided light leaves from either face with equal chance (Emitters::EmitFromTriangle).
        const bool back = emitter.direction.w != 0.0 && u[3] < 0.5;
        photon.direction = ToWorld(FrameFromNormal(emitter.direction.xyz), SampleCosineHemisphere(u[4], u[5]));
        const vec3 normal = back ? -emitter.direction.xyz : emitter.direction.xyz;
        if (back) photon.direction = -photon.direction;
        photon.origin = OffsetRayOrigin(point, normal);
        photon.flux *= EmissionTexel(emitter, b);
        return photon;
    }
    const float u1 = u[1], u2 = u[2];
    if (kHasPointLights && kind == kEmitterPoint) {
        photon.origin = emitter.position.xyz;
        photon.direction = SampleUniformSphere(u1, u2);
        photon.range = emitter.radiance.w;
    } else if (kHasSpotLights && kind == kEmitterSpot) {
        const vec3 local = SampleUniformCone(u1, u2, emitter.cone.y);
        photon.origin = emitter.position.xyz;
        photon.direction = ToWorld(FrameFromNormal(emitter.direction.xyz), local);
        photon.flux *= SpotFalloff(emitter, local.z);
        photon.range = emitter.radiance.w;
    } else if (kHasDirectionalLights && kind == kEmitterDirectional) {
        // A disk as wide as the scene's bounding sphere, just outside it, facing the light.
        const Frame frame = FrameFromNormal(emitter.direction.xyz);
        const vec2 d = SampleUniformDisk(u1, u2);
        const float radius = params.scene_sphere.w;
        photon.origin = params.scene_sphere.xyz - emitter.direction.xyz * (1.01 * radius) +
                        (frame.s * d.x + frame.t * d.y) * radius;
        photon.direction = emitter.direction.xyz;
    } else if (kHasEnvironment && kind == kEmitterEnvironment && HasPortal(emitter)) {
        // Through the portal: a direction over the hemisphere outside it, then a point of it:
        // flux L cos / pdf x its area (Emitters::EmitFromEnvironment).
        const vec3 n = PortalNormal(emitter);
        EnvironmentSample drawn;
        if (EnvironmentMapping(emitter) == kMappingUniform) {
            const vec3 local = SampleCosineHemisphere(u1, u2);
            drawn.toward = ToWorld(FrameFromNormal(n), local);
            drawn.radiance = emitter.radiance.xyz;
            drawn.pdf = local.z / kPi;
        } else {
            drawn = EnvironmentDrawFrom(emitter, floatBitsToUint(emitter.portal_v.w), u1, u2);
        }
        const float a = u[3], b = u[4];
        photon.origin = OffsetRayOrigin(
            emitter.position.xyz + emitter.portal_u.xyz * a + emitter.portal_v.xyz * b, n);
        photon.direction = -drawn.toward;
        const float cosine = dot(drawn.toward, n);
        photon.flux = drawn.pdf > 0 && cosine > 0
                          ? drawn.radiance * (cosine * emitter.portal_u.w / drawn.pdf) * emitter.power.w
                          : vec3(0);
    } else if (kHasEnvironment && kind == kEmitterEnvironment) {
        // A direction from the map, then a point of the bounding sphere's disk facing it, just
        // outside: flux L / pdf x pi r^2 (Emitters::EmitFromEnvironment).
        const EnvironmentSample drawn = EnvironmentDraw(emitter, u1, u2);
        const float radius = params.scene_sphere.w;
        photon.direction = -drawn.toward;
        if (!(drawn.pdf > 0)) {
            photon.origin = params.scene_sphere.xyz;
            photon.flux = vec3(0);
            return photon;
        }
        const Frame frame = FrameFromNormal(drawn.toward);
        const vec2 d = SampleUniformDisk(u[3], u[4]);
        photon.origin = params.scene_sphere.xyz + drawn.toward * (1.01 * radius) +
                        (frame.s * d.x + frame.t * d.y) * radius;
        photon.flux = drawn.radiance * (kPi * radius * radius / drawn.pdf) * emitter.power.w;
    } else if (kHasImageLights && kind == kEmitterGoniometric) {
        // Intensity over the light's sphere is an environment map (Emitters::ImageSampler).
        const EnvironmentSample drawn = EnvironmentDraw(emitter, u1, u2);
        photon.origin = emitter.position.xyz;
        photon.direction = drawn.toward;
        photon.flux = drawn.pdf > 0 ? drawn.radiance / drawn.pdf * emitter.power.w : vec3(0);
    } else if (kHasImageLights && kind == kEmitterProjection) {
        photon.origin = emitter.position.xyz;
        ProjectionEmit(emitter, u1, u2, u[3], photon.direction, photon.flux);
        photon.flux *= emitter.power.w;
    }
    return photon;
}

float[kEmissionNumbers] DrawEmissionNumbers(inout Pcg32 rng) {
    float u[kEmissionNumbers];
    for (uint i = 0; i < kEmissionNumbers; ++i) u[i] = Pcg32NextFloat(rng);
    return u;
}

struct LightSample {
    vec3 origin, direction;  // the shadow ray, toward the light
    float distance;          // how far the shadow ray goes
    vec3 radiance_over_pdf;  // incident radiance / pdf(solid angle), receiver cosine excluded
    float pdf;               // that pdf, the pick included; 0 for a punctual light
};

// Where u lies within emitter `index`'s share of [0, 1), rescaled to [0, 1)
// (DiscreteDistribution::Remap, in float here).
float RemapPick(float u, uint index) {
    const float below = index == 0 ? 0.0 : emitter_cdf[index - 1];
    return clamp((u - below) * emitters[index].power.w, 0.0, 0.99999994);
}

// One light sample at receiver p with facing normal n (Emitters::SampleDirect); false where it
// carries no light. `pick` chooses the emitter, `u` the point on it; with `pick_from_u`, u.x
// chooses it and is rescaled within its share.
bool SampleLightFrom(vec3 p, vec3 n, float pick, vec2 u, bool pick_from_u,
                     out LightSample sample_out) {
    const uint index = PickEmitter(pick_from_u ? u.x : pick);
    const GpuEmitter emitter = emitters[index];
    const uint kind = EmitterKind(emitter);
    const float u1 = pick_from_u ? RemapPick(u.x, index) : u.x, u2 = u.y;
    sample_out.origin = OffsetRayOrigin(p, n);
    sample_out.distance = kInfinity;
    sample_out.pdf = 0;
    vec3 to_light = vec3(0);
    vec3 radiance_over_pdf = vec3(0);
    if (kHasTriangleLights && kind == kEmitterTriangle) {
        const vec2 b = SampleUniformTriangle(u1, u2);
        const vec3 point = emitter.position.xyz + emitter.edge1.xyz * b.x + emitter.edge2.xyz * b.y;
        to_light = point - sample_out.origin;
        const float distance_sq = dot(to_light, to_light);
        sample_out.distance = sqrt(distance_sq);
        to_light /= sample_out.distance;
        const float cos_light = CosineToward(emitter, to_light);
        if (!(cos_light > 0) || !(distance_sq > 0)) return false;
        radiance_over_pdf = emitter.radiance.xyz * EmissionTexel(emitter, b) *
                            (cos_light * emitter.edge1.w / distance_sq);
        // An emitter cut out everywhere is found by light sampling alone: no MIS weight.
        sample_out.pdf = emitter.edge2.w != 0.0 ? 0.0 : distance_sq / (cos_light * emitter.edge1.w * emitter.power.w);
    } else if (kHasDirectionalLights && kind == kEmitterDirectional) {
        to_light = -emitter.direction.xyz;
        radiance_over_pdf = emitter.radiance.xyz;
    } else if (kHasEnvironment && kind == kEmitterEnvironment && HasPortal(emitter)) {
        // A point of the portal, uniform: area pdf 1/A, in solid angle d^2 / (cos A).
        to_light = emitter.position.xyz + emitter.portal_u.xyz * u1 + emitter.portal_v.xyz * u2 -
                   sample_out.origin;
        const float distance_sq = dot(to_light, to_light);
        to_light /= sqrt(distance_sq);
        const float cosine = dot(to_light, PortalNormal(emitter));
        if (!(cosine > 0) || !(distance_sq > 0)) return false;
        radiance_over_pdf = EnvironmentRadiance(emitter, to_light) *
                            (cosine * emitter.portal_u.w / distance_sq);
        sample_out.pdf = distance_sq / (cosine * emitter.portal_u.w * emitter.power.w);
    } else if (kHasEnvironment && kind == kEmitterEnvironment) {
        const EnvironmentSample drawn = EnvironmentDraw(emitter, u1, u2);
        if (!(drawn.pdf > 0)) return false;
        to_light = drawn.toward;
        radiance_over_pdf = drawn.radiance / drawn.pdf;
        sample_out.pdf = drawn.pdf / emitter.power.w;
    } else if ((kHasPointLights && kind == kEmitterPoint) || (kHasSpotLights && kind == kEmitterSpot) ||
               (kHasImageLights && (kind == kEmitterGoniometric || kind == kEmitterProjection))) {
        to_light = emitter.position.xyz - sample_out.origin;
        const float distance_sq = dot(to_light, to_light);
        sample_out.distance = sqrt(distance_sq);
        to_light /= sample_out.distance;
        if (!(distance_sq > 0)) return false;
        vec3 intensity = emitter.radiance.xyz;
        if (kHasSpotLights && kind == kEmitterSpot)
            intensity *= SpotFalloff(emitter, -dot(to_light, emitter.direction.xyz));
        if (kHasImageLights && kind == kEmitterGoniometric)
            intensity = EnvironmentRadiance(emitter, -to_light);
        if (kHasImageLights && kind == kEmitterProjection)
            intensity = ProjectionIntensity(emitter, -to_light);
        radiance_over_pdf = intensity * (RangeWindow(sample_out.distance, emitter.radiance.w) / distance_sq);
    }
    if (!(dot(to_light, n) > 0) || MaxComponent(radiance_over_pdf) <= 0) return false;
    sample_out.direction = to_light;
    sample_out.distance *= 1.0 - 1e-4;  // stop short of the light, by a margin that scales
    sample_out.radiance_over_pdf = radiance_over_pdf * emitter.power.w;
    return true;
}

// What a ray from p finds where it hits point on_light of triangle `hit` (Emitters::HitEmitter):
// the radiance emitted toward p and the density with which SampleLight picks that point; both
// 0 where the triangle emits nothing or not toward p.
vec3 HitEmitter(RayHit hit, vec3 p, vec3 on_light, out float pdf) {
    pdf = 0;
    if (kHasCurves && CurveOfSlot(hit.triangle) != ~kCurveBit) return vec3(0);  // curves never emit
    const uint index = floatBitsToUint(shading[floatBitsToUint(triangles[hit.triangle].p0.w)].normal.w);
    if (index == kNoEmitter) return vec3(0);
    const GpuEmitter emitter = emitters[index];
    const vec3 to_light = on_light - p;
    const float distance_sq = dot(to_light, to_light);
    const float cos_light = CosineToward(emitter, to_light / sqrt(distance_sq));
    if (!(cos_light > 0) || !(distance_sq > 0)) return vec3(0);
    pdf = distance_sq / (cos_light * emitter.edge1.w * emitter.power.w);
    return emitter.radiance.xyz * EmissionTexel(emitter, vec2(hit.b1, hit.b2));
}

// What a ray from `origin` that escapes the scene toward unit direction `toward` finds
// (Emitters::Escaped): the environment's radiance and the density with which SampleLight
// picks that direction; both 0 where its portal does not let the ray out.
vec3 EscapedRay(vec3 origin, vec3 toward, out float pdf) {
    const GpuEmitter environment = EnvironmentEmitter();
    if (HasPortal(environment)) {
        pdf = 0;
        const vec3 n = PortalNormal(environment);
        float t;
        if (!PortalExit(environment.position.xyz, environment.portal_u.xyz,
                        environment.portal_v.xyz, n, origin, toward, t))
            return vec3(0);
        pdf = t * t / (dot(toward, n) * environment.portal_u.w * environment.power.w);
        return EnvironmentRadiance(environment, toward);
    }
    pdf = EnvironmentPdf(environment, toward) / environment.power.w;
    return EnvironmentRadiance(environment, toward);
}
