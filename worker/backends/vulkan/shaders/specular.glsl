// Specular scattering, as core/scene/specular.h (Fresnel and refraction from
// core/shared/path_sampling.h): the branch is chosen with its Fresnel probability, so the
// carried weight is the tint alone. Materials the scene lacks are compiled out.
struct SpecularBounce {
    vec3 direction;
    vec3 weight;
    bool transmitted;
};

// d arrives at a specular surface of `material` whose front-side shading normal is `normal`.
SpecularBounce ScatterSpecular(GpuMaterial material, vec3 d, vec3 normal, bool front_facing, vec3 tint, float u) {
    const vec3 n = front_facing ? normal : -normal;  // facing the incident side
    const float ior = material.base_color.w;
    const float cos_i = -dot(d, n);
    float reflect_probability = 1.0;
    if (kHasDielectric && material.type == kMaterialDielectric) {
        // Front faces lead into the glass.
        reflect_probability = FresnelDielectric(cos_i, front_facing ? 1.0 / ior : ior);
    } else if (kHasThinDielectric && material.type == kMaterialThinDielectric) {
        const float r = FresnelDielectric(cos_i, 1.0 / ior);
        reflect_probability = 2.0 * r / (1.0 + r);
    }
    const SpecularBounce reflected =
        SpecularBounce(d + n * (2.0 * cos_i), material.type == kMaterialMirror ? tint : vec3(1.0), false);
    if (u < reflect_probability) return reflected;
    if (kHasThinDielectric && material.type == kMaterialThinDielectric) return SpecularBounce(d, tint, true);
    // Refraction through solid glass; reflected instead should rounding disagree with the
    // Fresnel term about total internal reflection.
    vec3 refracted;
    if (!Refract(d, n, front_facing ? 1.0 / ior : ior, refracted)) return reflected;
    return SpecularBounce(refracted, tint, true);
}
