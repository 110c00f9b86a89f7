// The path tracer's vertex (core/render/path_tracer.cpp on the CPU: next-event estimation
// weighed against BSDF sampling by the power heuristic at diffuse and rough-metal vertices,
// coats walked as TraceCoatedBase does), and what the pixel integrators share about diffuse
// surfaces. Two designs run it: the megakernel (pixel_trace.comp) follows a path's vertices in
// one thread; the wavefront (path_wavefront.comp) keeps paths in a buffer and runs a kernel a
// stage, shading each class of vertex (kVertex*) in a pipeline of its own. The includer brings
// common, trace, lights, specular and direct.glsl.

// The class of vertex a pipeline shades (kVertexAny: all; a wavefront shading stage: one, so
// that the others' code is compiled out).
layout(constant_id = kSpecVertexClass) const uint kVertexClass = kVertexAny;

// A light sample from p, normal n, its numbers from rng (Emitters::SampleDirect), and whether it
// is unoccluded.
bool SampleVisibleLight(vec3 p, vec3 n, inout Pcg32 rng, out LightSample light) {
    const float pick = Pcg32NextFloat(rng), u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
    RayHit unused;
    return SampleLightFrom(p, n, pick, vec2(u1, u2), false, light) &&
           !TraceRay(light.origin, light.direction, light.distance, true, unused);
}

// What a camera path arriving along -wo at a glossy vertex (GlossyToPunctualLights) sees of
// punctual lights (PunctualLightOnGloss in core/scene/glossy_lights.h): one light sample, kept
// where it picked a punctual light, f |cos| times its radiance over pdf where its shadow ray is
// clear; rough glass takes a light on either side. Three numbers, then a coated conductor's.
vec3 PunctualLightOnGloss(Bsdf bsdf, Surface surface, bool front_facing, vec3 wo, inout Pcg32 rng) {
    const vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const float pick = Pcg32NextFloat(rng), u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
    LightSample light;
    bool found = SampleLightFrom(surface.position, geometric, pick, vec2(u1, u2), false, light);
    if (!found && kHasRoughDielectric && bsdf.type == kMaterialRoughDielectric && !IsCoated(bsdf))
        found = SampleLightFrom(surface.position, -geometric, pick, vec2(u1, u2), false, light);
    if (!found || light.pdf > 0.0) return vec3(0.0);
    const vec3 f = GlossyResponse(bsdf, surface.base_color, surface.shading_normal, front_facing, wo, light.direction, rng);
    RayHit unused;
    if (!(MaxComponent(f) > 0.0) || TraceRay(light.origin, light.direction, light.distance, true, unused))
        return vec3(0.0);
    return f * light.radiance_over_pdf;
}

// The light leaving a coated diffuse base toward a path that entered the coat carrying
// `entered` (TraceCoatedBase): light sampling through the coat at each visit, then a cosine
// bounce inside that the coat lets out or turns back. Sets the path leaving the coat; false
// where it ends inside.
bool TraceCoatedBase(Surface surface, bool front_facing, Coat coat, vec3 entered, inout Pcg32 rng,
                     inout vec3 radiance, out vec3 throughput, out vec3 origin, out vec3 direction) {
    vec3 inside = entered * CoatInside(coat);  // a layer's radiance inside is ior^2 times larger
    const vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
    const vec3 geometric = front_facing ? surface.geometric_normal : -surface.geometric_normal;
    const Frame frame = FrameFromNormal(normal);
    const vec3 base_color = surface.base_color;
    throughput = vec3(0);
    origin = surface.position;
    direction = normal;
    for (uint visit = 0; visit < coat.depth; ++visit) {  // each with its chance to leave
        LightSample light;
        if (SampleVisibleLight(surface.position, normal, rng, light)) {
            const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
            const float through = CoatTransmittance(coat, ToLocal(frame, light.direction), u1, u2);
            radiance += inside * base_color / kPi * light.radiance_over_pdf * (dot(light.direction, normal) * through);
        }
        const float survive = min(1.0, MaxComponent(base_color));
        if (!(Pcg32NextFloat(rng) < survive)) return false;
        inside *= base_color / survive;
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const vec3 up = SampleCosineHemisphere(u1, u2);
        const CoatLeaving leaving = LeaveCoatAt(coat, frame, up, rng);
        inside *= leaving.weight;
        if (!(MaxComponent(inside) > 0.0)) return false;
        if (leaving.escaped) {
            direction = leaving.direction;
            if (!(dot(direction, geometric) > 0)) return false;
            throughput = inside / CoatInside(coat);
            origin = OffsetRayOrigin(surface.position, geometric);
            return true;
        }
    }
    return false;
}

// A path between vertices: the ray it follows next and what it has gathered.
struct PathState {
    vec3 origin, direction;
    vec3 radiance, throughput;
    // Emission found by a specular bounce (or seen directly) counts in full; after a diffuse or
    // rough bounce it is weighed against light sampling, which finds it too.
    bool specular_bounce;
    bool coat_exit;  // the last bounce left a coated base: light sampling found its light
    float bsdf_pdf;  // of the last diffuse or rough bounce, solid angle
    vec3 bounced_at;
    uint depth;        // surfaces met so far
    float refraction;  // the refractions' scales of radiance in throughput, out of Russian roulette
};

PathState BeginPath(vec3 origin, vec3 direction) {
    return PathState(origin, direction, vec3(0), vec3(1), true, false, 0.0, origin, 0, 1.0);
}

// The class of vertex a material makes.
uint VertexClass(Bsdf bsdf) {
    if (bsdf.type == kMaterialDiffuse) return IsCoated(bsdf) ? kVertexCoated : kVertexDiffuse;
    if (kHasRoughConductor && bsdf.type == kMaterialRoughConductor && !IsCoated(bsdf)) return kVertexRough;
    return kVertexSpecular;
}

// The vertex where the path's ray found `hit` (`found` false: it escaped): emission found
// there, light sampled, the next ray chosen. False where the path ends.
bool PathVertex(inout PathState path, bool found, RayHit hit, inout Pcg32 rng) {
    const vec3 direction = path.direction;
    if (!found) {
        if (kHasEnvironment) {
            float pdf;
            const vec3 escaped = EscapedRay(path.origin, direction, pdf);
            const float weight = path.specular_bounce ? 1.0
                                 : path.coat_exit     ? (pdf > 0 ? 0.0 : 1.0)
                                                      : PowerHeuristic(path.bsdf_pdf, pdf);
            if (MaxComponent(escaped) > 0.0) path.radiance += path.throughput * escaped * weight;
        }
        return false;
    }
    const Surface surface = SurfaceAt(hit);
    const GpuMaterial material = ShadingMaterial(surface);
    const Bsdf bsdf = BsdfOf(material);
    const bool front_facing = dot(direction, surface.geometric_normal) < 0;
    if (kHasAbsorption)
        path.throughput *= SegmentTransmittance(material.absorption.xyz, material.outside_absorption.xyz, front_facing, hit.t);
    if (kHasTriangleLights) {
        float light_pdf;
        const vec3 emitted = HitEmitter(hit, path.specular_bounce ? path.origin : path.bounced_at, surface.position, light_pdf);
        if (MaxComponent(emitted) > 0.0) {
            float weight = 1.0;
            if (!path.specular_bounce)
                weight = path.coat_exit ? (light_pdf > 0 ? 0.0 : 1.0) : PowerHeuristic(path.bsdf_pdf, light_pdf);
            path.radiance += path.throughput * emitted * weight;
        }
    }
    if (path.depth >= pixel_job.max_depth) return false;
    const uint kind = kVertexClass == kVertexAny ? VertexClass(bsdf) : kVertexClass;
    const vec3 base_color = surface.base_color;
    // Punctual lights on a glossy surface, which no path finds; bare rough metal's light
    // sampling below takes every light.
    if (kind != kVertexDiffuse && kind != kVertexRough && GlossyToPunctualLights(bsdf))
        path.radiance += path.throughput * PunctualLightOnGloss(bsdf, surface, front_facing, -direction, rng);
    const CoatArrival arrival = kind == kVertexCoated
                                    ? ArriveAtCoat(bsdf, direction, surface.shading_normal, front_facing, rng)
                                    : CoatArrival(true, 1.0, SpecularBounce(direction, vec3(0.0), false));
    if (kind == kVertexDiffuse) {
        // Light sampled on the path's side and, through a translucent surface, on the other;
        // the bounce on one of them, chosen with its probability, against whose density
        // each side's light sample is weighed.
        const float through = IsTranslucent(bsdf) ? TransmitProbability(base_color, bsdf.transmittance) : 0.0;
        for (int other = 0; other < 2; ++other) {
            if (other == 1 && !(through > 0)) break;
            const vec3 facing = front_facing != (other == 1) ? surface.shading_normal : -surface.shading_normal;
            const vec3 albedo = other == 1 ? bsdf.transmittance : base_color;
            const float chosen = other == 1 ? through : 1.0 - through;
            LightSample light;
            if (SampleVisibleLight(surface.position, facing, rng, light)) {
                const float cosine = dot(light.direction, facing);
                const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, chosen * cosine / kPi) : 1.0;
                path.radiance += path.throughput * (albedo / kPi) * light.radiance_over_pdf * (cosine * weight);
            }
        }
        const DiffuseSide side = ChooseDiffuseSide(bsdf, base_color, rng);
        const bool toward = front_facing != side.through;
        const vec3 normal = toward ? surface.shading_normal : -surface.shading_normal;
        const vec3 geometric = toward ? surface.geometric_normal : -surface.geometric_normal;
        const float u1 = Pcg32NextFloat(rng), u2 = Pcg32NextFloat(rng);
        const vec3 local = SampleCosineHemisphere(u1, u2);
        path.direction = ToWorld(FrameFromNormal(normal), local);
        if (!(dot(path.direction, geometric) > 0)) return false;  // the shading normal pointed it inside
        path.throughput *= side.albedo;
        path.bsdf_pdf = (side.through ? through : 1.0 - through) * local.z / kPi;
        path.bounced_at = surface.position;
        path.specular_bounce = false;
        path.coat_exit = false;
        path.origin = OffsetRayOrigin(surface.position, geometric);
    } else if (kind == kVertexCoated && arrival.at_base) {
        if (!TraceCoatedBase(surface, front_facing, bsdf.coat, path.throughput * arrival.weight, rng, path.radiance,
                             path.throughput, path.origin, path.direction))
            return false;
        path.bounced_at = surface.position;
        path.specular_bounce = false;
        path.coat_exit = true;
    } else if (kind == kVertexCoated) {
        // The coat's reflection, found by its own sampling alone, as specular bounces are.
        path.throughput *= arrival.reflected.weight;
        path.specular_bounce = true;
        path.coat_exit = false;
        path.origin = OffsetRayOrigin(surface.position, front_facing ? surface.geometric_normal : -surface.geometric_normal);
        path.direction = arrival.reflected.direction;
    } else if (kind == kVertexRough) {
        // Light sampling weighed against the GGX lobe's own sampling.
        const vec3 normal = front_facing ? surface.shading_normal : -surface.shading_normal;
        const vec3 wo = -direction;
        LightSample light;
        if (SampleVisibleLight(surface.position, normal, rng, light)) {
            const RoughReflection f = EvaluateRoughConductor(bsdf, base_color, normal, wo, light.direction);
            const float weight = light.pdf > 0 ? PowerHeuristic(light.pdf, f.pdf) : 1.0;
            path.radiance += path.throughput * f.value * light.radiance_over_pdf * weight;
        }
        const SpecularBounce bounce = ScatterNonDiffuse(bsdf, direction, surface.shading_normal, front_facing,
                                                        surface.base_color, rng, kCarriesRadiance);
        path.throughput *= bounce.weight;
        path.bsdf_pdf = EvaluateRoughConductor(bsdf, base_color, normal, wo, bounce.direction).pdf;
        path.bounced_at = surface.position;
        path.specular_bounce = false;
        path.coat_exit = false;
        path.origin = OffsetRayOrigin(surface.position, front_facing ? surface.geometric_normal : -surface.geometric_normal);
        path.direction = bounce.direction;
    } else {
        // Specular surfaces, and rough glass, whose light is found by its own sampling alone.
        const SpecularBounce bounce = ScatterNonDiffuse(bsdf, direction, surface.shading_normal, front_facing,
                                                        surface.base_color, rng, kCarriesRadiance);
        path.throughput *= bounce.weight;
        if (bounce.transmitted) path.refraction *= RefractionOf(bsdf, front_facing);
        path.specular_bounce = true;
        path.coat_exit = false;
        path.origin = OffsetRayOrigin(surface.position, front_facing == bounce.transmitted ? -surface.geometric_normal
                                                                                           : surface.geometric_normal);
        path.direction = bounce.direction;
    }
    if (path.depth >= pixel_job.roulette_depth) {
        const float survive = min(1.0, MaxComponent(path.throughput) / path.refraction);
        if (!(Pcg32NextFloat(rng) < survive)) return false;
        path.throughput /= survive;
    }
    if (all(equal(path.throughput, vec3(0)))) return false;
    ++path.depth;
    return true;
}
