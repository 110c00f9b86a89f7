// The scene analysis.
#include "core/scene/scene_features.h"

#include <vector>

#include "absl/strings/str_join.h"
#include "core/shared/coat.h"
#include "core/shared/conductor.h"

namespace pf {

SceneFeatures SceneFeatures::All() {
    SceneFeatures all;
    for (bool* flag : {&all.mirror,          &all.dielectric,          &all.thin_dielectric,
                       &all.rough_conductor, &all.rough_dielectric,    &all.coats,
                       &all.cut_outs,        &all.alpha_textures,      &all.mixes,
                       &all.textures,        &all.vertex_colors,       &all.roughness_textures,
                       &all.mix_textures,    &all.fresnel_mixes,       &all.conductor_fresnel,
                       &all.absorption,      &all.translucent,         &all.sheen,
                       &all.sheen_textures,  &all.procedural_textures, &all.smooth_normals,
                       &all.curves,          &all.shading_detail,      &all.triangle_lights,
                       &all.point_lights,    &all.spot_lights,         &all.directional_lights,
                       &all.environment,     &all.textured_lights,     &all.image_lights,
                       &all.caustics})
        *flag = true;
    return all;
}

std::string SceneFeatures::ToString() const {
    std::vector<std::string> parts = {"diffuse"};
    if (mirror) parts.push_back("mirror");
    if (dielectric) parts.push_back("glass");
    if (thin_dielectric) parts.push_back("thin glass");
    if (rough_conductor) parts.push_back("rough metal");
    if (rough_dielectric) parts.push_back("rough glass");
    if (coats) parts.push_back("coated");
    if (fresnel_mixes) parts.push_back("specular over diffuse");
    if (conductor_fresnel) parts.push_back("metal Fresnel");
    if (absorption) parts.push_back("absorbing media");
    if (translucent) parts.push_back("diffuse transmission");
    if (sheen) parts.push_back("sheen");
    if (sheen_textures) parts.push_back("sheen textures");
    if (cut_outs) parts.push_back("cut-outs");
    if (mixes) parts.push_back("mixed materials");
    if (textures) parts.push_back("textures");
    if (vertex_colors) parts.push_back("vertex colours");
    if (roughness_textures) parts.push_back("roughness textures");
    if (mix_textures) parts.push_back("textured mixes");
    if (procedural_textures) parts.push_back("procedural textures");
    if (smooth_normals) parts.push_back("smooth normals");
    if (curves) parts.push_back("curves");
    if (shading_detail) parts.push_back("normal or bump maps");
    if (triangle_lights) parts.push_back("area lights");
    if (point_lights) parts.push_back("point lights");
    if (spot_lights) parts.push_back("spot lights");
    if (directional_lights) parts.push_back("directional lights");
    if (environment) parts.push_back("environment light");
    if (textured_lights) parts.push_back("textured lights");
    if (image_lights) parts.push_back("goniometric or projection lights");
    if (caustics) parts.push_back("caustics");
    return absl::StrJoin(parts, ", ");
}

SceneFeatures AnalyseFeatures(const Scene& scene, const Emitters& emitters) {
    SceneFeatures features;
    features.vertex_colors = !scene.colors.empty();
    std::vector<bool> used(scene.materials.size(), false);
    for (const Triangle& triangle : scene.triangles) {
        used[triangle.material] = true;
        features.smooth_normals |= triangle.smooth;
    }
    for (const Curve& curve : scene.curves) used[curve.material] = true;
    features.curves = !scene.curves.empty();
    // A mix's materials (which come before it) are used where it is.
    for (size_t m = scene.materials.size(); m-- > 0;)
        if (used[m] && scene.materials[m].type == MaterialType::kMix)
            used[scene.materials[m].mix_first] = used[scene.materials[m].mix_second] = true;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        if (!used[m]) continue;
        const Material& material = scene.materials[m];
        features.mirror |= material.type == MaterialType::kMirror;
        features.dielectric |= material.type == MaterialType::kDielectric;
        features.thin_dielectric |= material.type == MaterialType::kThinDielectric;
        features.rough_conductor |= material.type == MaterialType::kRoughConductor;
        features.rough_dielectric |= material.type == MaterialType::kRoughDielectric;
        features.coats |= material.HasCoat();
        features.cut_outs |= material.HasCutOuts();
        features.alpha_textures |= material.alpha_texture != kNoTexture;
        features.mixes |= material.type == MaterialType::kMix;
        features.textures |=
            material.base_color_texture != kNoTexture ||
            (material.IsTranslucent() && material.transmittance_texture != kNoTexture);
        features.roughness_textures |= material.roughness_texture != kNoTexture;
        features.mix_textures |= material.mix_texture != kNoTexture;
        features.fresnel_mixes |= material.HasCoat() && material.coat_kind == gpu::kCoatFresnelMix;
        features.conductor_fresnel |= (material.type == MaterialType::kMirror ||
                                       material.type == MaterialType::kRoughConductor) &&
                                      material.conductor != gpu::kConductorTint;
        features.absorption |= material.HasVolume();
        features.translucent |= material.IsTranslucent();
        features.sheen |= material.HasSheen();
        features.sheen_textures |=
            material.HasSheen() && (material.sheen_texture != kNoTexture ||
                                    material.sheen_roughness_texture != kNoTexture);
        features.shading_detail |= material.HasShadingDetail();
        for (const int32_t texture : material.Textures())
            features.procedural_textures |= texture != kNoTexture && scene.textures[texture] &&
                                            scene.textures[texture]->IsProcedural();
    }
    for (const Emitters::Record& record : emitters.Records()) {
        if (record.kind == EmitterKind::kTriangle) {
            features.triangle_lights = true;
            features.textured_lights |= record.texture != kNoTexture;
            continue;
        }
        if (record.kind == EmitterKind::kEnvironment) {
            features.environment = true;
            continue;
        }
        switch (scene.lights[record.light].type) {
            case LightType::kPoint:
                features.point_lights = true;
                break;
            case LightType::kSpot:
                features.spot_lights = true;
                break;
            case LightType::kDirectional:
                features.directional_lights = true;
                break;
            case LightType::kGoniometric:
            case LightType::kProjection:
                features.image_lights = true;
                break;
        }
    }
    return features;
}

}  // namespace pf
