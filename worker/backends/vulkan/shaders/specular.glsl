// Specular scattering, as core/scene/specular.h: the branch is chosen with its Fresnel
// probability, so the carried weight is the tint alone. Materials the scene lacks are
// compiled out.
float FresnelDielectric(float cos_incident, float eta) {
    cos_incident = clamp(cos_incident, 0.0, 1.0);
    const float sin_t_sq = eta * eta * (1.0 - cos_incident * cos_incident);
    if (sin_t_sq >= 1.0) return 1.0;
    const float cos_t = sqrt(1.0 - sin_t_sq);
    const float r_parallel = (cos_incident - eta * cos_t) / (cos_incident + eta * cos_t);
    const float r_perpendicular = (eta * cos_incident - cos_t) / (eta * cos_incident + cos_t);
    return 0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

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
    const float eta = front_facing ? 1.0 / ior : ior;
    const float sin_t_sq = eta * eta * max(0.0, 1.0 - cos_i * cos_i);
    if (sin_t_sq >= 1.0) return reflected;
    const float cos_t = sqrt(1.0 - sin_t_sq);
    return SpecularBounce(normalize(d * eta + n * (eta * cos_i - cos_t)), tint, true);
}
