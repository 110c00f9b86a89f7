// Direct light at a diffuse point, as core/ppm/direct_light.cpp takes it on the CPU (its
// StartDirectLight and FinishDirectLight): a light sample with its shadow ray and, in a scene
// whose lights rays can find (emitting triangles, an environment), a cosine-distributed ray,
// the two weighed by the power heuristic; under a coat, times what it lets through of each.

// Whether the cosine ray is traced: it takes two numbers after the light sample's three.
const bool kLightsFoundByRays = kHasTriangleLights || kHasEnvironment;

// The irradiance at p, unit normal n on the side light arrives from, under the coat of material
// `coat` (or kNoCoat). The light sample takes `pick` and `light_u` (with `pick_from_u`, light_u.x
// picks the emitter too, SampleLightFrom), the cosine ray `cosine_u`; a rough coat's microfacet
// is drawn from `rng` last.
vec3 DirectIrradiance(vec3 p, vec3 n, uint coat, float pick, vec2 light_u, bool pick_from_u,
                      vec2 cosine_u, inout Pcg32 rng) {
    LightSample light;
    vec3 light_part = vec3(0), ray_part = vec3(0);
    vec3 ray_direction = n;
    RayHit hit;
    if (SampleLightFrom(p, n, pick, light_u, pick_from_u, light) &&
        !TraceRay(light.origin, light.direction, light.distance, true, hit)) {
        const float cosine = dot(light.direction, n);
        // A punctual light (pdf 0) is found by light sampling alone.
        const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, cosine / kPi) : 1.0;
        light_part = light.radiance_over_pdf * (cosine * weight);
    }
    if (kLightsFoundByRays) {
        ray_direction = ToWorld(FrameFromNormal(n), SampleCosineHemisphere(cosine_u.x, cosine_u.y));
        const vec3 origin = OffsetRayOrigin(p, n);
        float pdf = 0;
        vec3 radiance = vec3(0);
        if (TraceRay(origin, ray_direction, kInfinity, false, hit)) {
            if (kHasTriangleLights) radiance = HitEmitter(hit, origin, origin + ray_direction * hit.t, pdf);
        } else if (kHasEnvironment) {
            radiance = EscapedRay(origin, ray_direction, pdf);
        }
        // L cos / (cos / pi): the cosine ray's own weight is pi.
        if (pdf > 0) ray_part = radiance * (kPi * PowerHeuristic(dot(ray_direction, n) / kPi, pdf));
    }
    // Under a coat, what it lets through of each (CoatFactor).
    if (kHasCoats && coat != kNoCoat) {
        const Coat layer = CoatOf(materials[coat]);
        float u1 = 0, u2 = 0;
        if (layer.alpha > 0.0) u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const Frame frame = FrameFromNormal(n);
        if (MaxComponent(light_part) > 0.0) light_part *= CoatTransmittance(layer, ToLocal(frame, light.direction), u1, u2);
        if (MaxComponent(ray_part) > 0.0) ray_part *= CoatTransmittance(layer, ToLocal(frame, ray_direction), u1, u2);
    }
    return light_part + ray_part;
}
