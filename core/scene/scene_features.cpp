// The scene analysis.
#include "core/scene/scene_features.h"

#include <vector>

#include "absl/strings/str_join.h"

namespace pf {

SceneFeatures SceneFeatures::All() {
    return {true, true, true, true, true, true, true, true, true, true};
}

std::string SceneFeatures::ToString() const {
    std::vector<std::string> parts = {"diffuse"};
    if (mirror) parts.push_back("mirror");
    if (dielectric) parts.push_back("glass");
    if (thin_dielectric) parts.push_back("thin glass");
    if (textures) parts.push_back("textures");
    if (smooth_normals) parts.push_back("smooth normals");
    if (triangle_lights) parts.push_back("area lights");
    if (point_lights) parts.push_back("point lights");
    if (spot_lights) parts.push_back("spot lights");
    if (directional_lights) parts.push_back("directional lights");
    if (caustics) parts.push_back("caustics");
    return absl::StrJoin(parts, ", ");
}

SceneFeatures AnalyseFeatures(const Scene& scene, const Emitters& emitters) {
    SceneFeatures features;
    std::vector<bool> used(scene.materials.size(), false);
    for (const Triangle& triangle : scene.triangles) {
        used[triangle.material] = true;
        features.smooth_normals |= triangle.smooth;
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        if (!used[m]) continue;
        const Material& material = scene.materials[m];
        features.mirror |= material.type == MaterialType::kMirror;
        features.dielectric |= material.type == MaterialType::kDielectric;
        features.thin_dielectric |= material.type == MaterialType::kThinDielectric;
        features.textures |= material.base_color_texture != kNoTexture;
    }
    for (const Emitters::Record& record : emitters.Records()) {
        if (record.is_triangle) {
            features.triangle_lights = true;
            continue;
        }
        switch (scene.lights[record.light].type) {
            case LightType::kPoint: features.point_lights = true; break;
            case LightType::kSpot: features.spot_lights = true; break;
            case LightType::kDirectional: features.directional_lights = true; break;
        }
    }
    return features;
}

}  // namespace pf
