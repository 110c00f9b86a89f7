// glTF's cameras and KHR_lights_punctual lights, placed by their nodes.
#pragma once

#include <tiny_gltf.h>

#include <string>

#include "absl/status/statusor.h"
#include "core/math/transform.h"
#include "core/scene/scene.h"

namespace pf {

// Light `light_index` of the file's KHR_lights_punctual lights at its node's `world` transform,
// radiometric (candela and lux at 683 lm/W). Errors begin with `path` and name the light.
absl::StatusOr<PunctualLight> GltfPunctualLight(const tinygltf::Model& model, int light_index,
                                                const Transform& world, const std::string& path);

// Sets `camera` to camera `camera_index` at its node's `world` transform (perspective or
// orthographic), keeping what the file does not say (the film's). Errors begin with `path`
// and name the camera; `camera` is unchanged then.
absl::Status SetGltfCamera(const tinygltf::Model& model, int camera_index, const Transform& world,
                           const std::string& path, Camera* camera);

// "kind 'name' (#index)", or "kind #index" for one without a name.
std::string DescribeGltf(const std::string& kind, int index, const std::string& name);

}  // namespace pf
