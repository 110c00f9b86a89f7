// glTF cameras and punctual lights.
#include "core/scene_io/gltf/gltf_lights.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

// Luminous efficacy of KHR_lights_punctual's photometric intensities (the maximum, at 555 nm).
constexpr double kLumensPerWatt = 683.0;

}  // namespace

std::string DescribeGltf(const std::string& kind, int index, const std::string& name) {
    return name.empty() ? absl::StrCat(kind, " #", index)
                        : absl::StrCat(kind, " '", name, "' (#", index, ")");
}

absl::StatusOr<PunctualLight> GltfPunctualLight(const tinygltf::Model& model, int light_index,
                                                const Transform& world, const std::string& path) {
    const auto Error = [&](const std::string& element, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(path, ": ", element, ": ", what));
    };
    if (light_index < 0 || light_index >= static_cast<int>(model.lights.size()))
        return Error(absl::StrCat("KHR_lights_punctual light #", light_index), "does not exist");
    const tinygltf::Light& source = model.lights[light_index];
    const std::string element = DescribeGltf("light", light_index, source.name);
    PunctualLight light;
    light.name = source.name;
    const Vec3d color = source.color.size() == 3
                            ? Vec3d(source.color[0], source.color[1], source.color[2])
                            : Vec3d(1.0);
    // KHR_lights_punctual's photometric units (candela for point and spot lights, lux for
    // directional ones) in watts, at 683 lm/W, the factor Blender's exporter multiplies watts by
    // (so its lights come back as they were made).
    light.intensity = Rgb(color * (source.intensity / kLumensPerWatt));
    if (!IsFinite(light.intensity) || MinComponent(light.intensity) < 0)
        return Error(element, "intensity or colour is negative, NaN or Inf");
    if (!(source.range >= 0 && std::isfinite(source.range)))
        return Error(element, "range must be finite and not negative");
    light.position = Vec3(world.ApplyPoint(Vec3d(0.0)));
    light.direction = Vec3(Normalize(world.ApplyVector(Vec3d(0, 0, -1))));
    if (!IsFinite(light.direction))
        return Error(element, "node transform collapses the light's direction");
    if (source.type == "point") {
        light.type = LightType::kPoint;
        light.range = static_cast<float>(source.range);
    } else if (source.type == "spot") {
        light.type = LightType::kSpot;
        light.range = static_cast<float>(source.range);
        light.cos_inner = static_cast<float>(std::cos(source.spot.innerConeAngle));
        light.cos_outer = static_cast<float>(std::cos(source.spot.outerConeAngle));
        if (!(source.spot.outerConeAngle > 0 && source.spot.outerConeAngle <= kPiD / 2 &&
              source.spot.innerConeAngle >= 0 &&
              source.spot.innerConeAngle < source.spot.outerConeAngle))
            return Error(element, "spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    } else if (source.type == "directional") {
        light.type = LightType::kDirectional;
        if (source.range > 0)
            spdlog::warn("{}: {}: a directional light has no range; ignored", path, element);
    } else {
        return Error(element, absl::StrCat("unknown light type '", source.type, "'"));
    }
    return light;
}

absl::Status SetGltfCamera(const tinygltf::Model& model, int camera_index, const Transform& world,
                           const std::string& path, Camera* camera_out) {
    const auto Error = [&](const std::string& element, const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(path, ": ", element, ": ", what));
    };
    if (camera_index >= static_cast<int>(model.cameras.size()))
        return Error(absl::StrCat("camera #", camera_index), "does not exist");
    const tinygltf::Camera& source = model.cameras[camera_index];
    const std::string element = DescribeGltf("camera", camera_index, source.name);
    Camera camera = *camera_out;
    if (source.type == "orthographic") {
        // xmag and ymag: half the view's width and height, world units.
        const double xmag = source.orthographic.xmag, ymag = source.orthographic.ymag;
        if (!(xmag > 0 && ymag > 0 && xmag < 1e30 && ymag < 1e30))
            return Error(element, "orthographic xmag and ymag must be positive and finite");
        camera.projection = Projection::kOrthographic;
        camera.window = {static_cast<float>(-xmag), static_cast<float>(xmag),
                         static_cast<float>(-ymag), static_cast<float>(ymag)};
        camera.aspect_ratio = static_cast<float>(xmag / ymag);
    } else if (source.type == "perspective") {
        camera.y_fov = static_cast<float>(source.perspective.yfov);
        camera.aspect_ratio = static_cast<float>(source.perspective.aspectRatio);
        if (!(camera.y_fov > 0 && camera.y_fov < kPi))
            return Error(element, "yfov must lie in (0, pi)");
    } else {
        return Error(element, absl::StrCat("type '", source.type,
                                           "' is unknown (perspective or orthographic)"));
    }
    camera.position = Vec3(world.ApplyPoint(Vec3d(0.0)));
    camera.forward = Vec3(Normalize(world.ApplyVector(Vec3d(0, 0, -1))));
    const Vec3 up_hint(Normalize(world.ApplyVector(Vec3d(0, 1, 0))));
    camera.right = Normalize(Cross(camera.forward, up_hint));
    camera.up = Cross(camera.right, camera.forward);
    if (!IsFinite(camera.position) || !IsFinite(camera.right) || !IsFinite(camera.up))
        return Error(element, "node transform is degenerate");
    *camera_out = camera;
    return absl::OkStatus();
}

}  // namespace pf
