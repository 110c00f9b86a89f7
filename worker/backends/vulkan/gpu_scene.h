// A scene as the Vulkan kernels read it: the BVH (Embree's builder), triangles in leaf
// order, shading data, materials, textures and emitters in the shared structs of
// core/shared/gpu_types.h, and the set of features the scene uses, which selects the
// kernels' specialisation. Plain arrays: no Vulkan here.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/emitters.h"
#include "core/scene/scene.h"
#include "core/scene/scene_features.h"
#include "core/shared/gpu_types.h"
#include "worker/backends/vulkan/kernels.h"

namespace pf::vk {

// The kernels' specialisation constants for a scene's features.
SpecConstants SpecConstantsFor(const SceneFeatures& features);

struct GpuScene {
    std::vector<gpu::GpuBvhNode> nodes;
    std::vector<gpu::GpuTriangle> triangles;
    std::vector<gpu::GpuTriangleShading> shading;
    std::vector<gpu::vec4> normals;
    std::vector<gpu::vec2> uvs;
    // Where the scene has normal or bump maps, or vertex colours (gpu::kBindingTangents).
    std::vector<gpu::vec4> tangents;
    std::vector<float> sheen_tables;  // gpu::kSheenTables, where the scene has sheen
    std::vector<gpu::GpuMaterial> materials;
    std::vector<gpu::GpuTexture> textures;
    std::vector<gpu::vec4> texels;
    std::vector<gpu::GpuEmitter> emitters;
    std::vector<float> emitter_cdf;
    // The images and sampling tables of the lights that have one (kBindingLightImage*: the
    // environment, goniometric and projection lights), empty without them, and the
    // environment's index into `emitters`.
    std::vector<gpu::vec4> light_image_texels;
    std::vector<float> light_image_tables;
    uint32_t environment_emitter = 0;
    SceneFeatures features;
    gpu::vec4 sphere{};   // the scene's bounding sphere, centre and radius (directional lights)
    float magnitude = 0;  // Bounds::Magnitude
    // The largest flux one photon can carry in any channel, W: albedos are at most 1, so no
    // path gains flux; the fixed-point tally's unit is a fraction of it.
    float max_photon_flux = 0;
};

absl::StatusOr<GpuScene> BuildGpuScene(const Scene& scene, const Emitters& emitters);

}  // namespace pf::vk
