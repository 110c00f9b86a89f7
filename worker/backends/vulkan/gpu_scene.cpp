// Flattening a scene into the shared GPU structs.
#include "worker/backends/vulkan/gpu_scene.h"

#include <bit>

#include "core/scene/mesh_builder.h"
#include "embree/bvh_builder.h"

namespace pf::vk {
namespace {

gpu::vec4 Vec4(const Vec3& v, float w = 0) { return {v.x, v.y, v.z, w}; }
gpu::vec4 Vec4(const Vec3& v, uint32_t w_bits) {
    return {v.x, v.y, v.z, std::bit_cast<float>(w_bits)};
}

void AddGeometry(const Scene& scene, const Emitters& emitters, const embree::GpuBvh& bvh,
                 GpuScene& gpu_scene) {
    for (uint32_t t : bvh.order) {
        const Triangle& triangle = scene.triangles[t];
        const Vec3& p0 = scene.positions[triangle.vertex[0]];
        gpu_scene.triangles.push_back({Vec4(p0, t), Vec4(scene.positions[triangle.vertex[1]] - p0),
                                       Vec4(scene.positions[triangle.vertex[2]] - p0)});
    }
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
        const Triangle& triangle = scene.triangles[t];
        // Emitters name world triangles, which flattening keeps first, under their indices.
        const int32_t emitter = emitters.EmitterOfTriangle(t);
        gpu_scene.shading.push_back(
            {Vec4(triangle.normal, emitter < 0 ? gpu::kNoEmitter : static_cast<uint32_t>(emitter)),
             {triangle.vertex[0], triangle.vertex[1], triangle.vertex[2],
              triangle.material | (triangle.smooth ? gpu::kSmoothBit : 0u)}});
    }
    // What no kernel of this scene reads is neither built nor uploaded.
    if (gpu_scene.features.smooth_normals)
        for (const Vec3& normal : scene.normals) gpu_scene.normals.push_back(Vec4(normal));
    if (gpu_scene.features.textures)
        for (const Point2& uv : scene.uvs) gpu_scene.uvs.push_back({uv.x, uv.y});
    for (const Material& material : scene.materials)
        gpu_scene.materials.push_back({Vec4(material.base_color, material.ior),
                                       static_cast<uint32_t>(material.type),
                                       material.base_color_texture, material.roughness, 0});
    if (!gpu_scene.features.textures && !gpu_scene.features.textured_lights) return;
    for (const std::shared_ptr<const Texture>& texture : scene.textures) {
        gpu_scene.textures.push_back(
            {static_cast<uint32_t>(gpu_scene.texels.size()), texture->width, texture->height, 0});
        for (const Rgb& texel : texture->texels) gpu_scene.texels.push_back(Vec4(texel));
    }
}

void AddEmitters(const Scene& scene, const Emitters& emitters, GpuScene& gpu_scene) {
    double cumulative = 0;
    for (const Emitters::Record& record : emitters.Records()) {
        gpu::GpuEmitter emitter{};
        const auto inverse_probability = static_cast<float>(1.0 / record.probability);
        if (record.kind == EmitterKind::kEnvironment) {
            const Environment& environment = *scene.environment;
            const auto bits = [](uint32_t value) { return std::bit_cast<float>(value); };
            emitter.position = Vec4(Vec3(0.0f), gpu::kEmitterEnvironment);
            emitter.edge1 = {bits(uint32_t(environment.image.width)),
                             bits(uint32_t(environment.image.height)),
                             bits(static_cast<uint32_t>(environment.mapping)), 0.0f};
            const auto& m = environment.to_map;
            emitter.edge2 = {m[0], m[1], m[2], 0.0f};
            emitter.direction = {m[3], m[4], m[5], 0.0f};
            emitter.cone = {m[6], m[7], m[8], 0.0f};
            emitter.radiance = Vec4(environment.scale);
            for (const Rgb& texel : environment.image.texels)
                gpu_scene.environment_texels.push_back(Vec4(texel));
            const EnvironmentSampler& sampler = emitters.EnvironmentSampling();
            for (const std::vector<float>* table :
                 {&sampler.RowCdf(), &sampler.TexelCdf(), &sampler.TexelProbability()})
                gpu_scene.environment_tables.insert(gpu_scene.environment_tables.end(),
                                                    table->begin(), table->end());
            gpu_scene.environment_emitter = static_cast<uint32_t>(gpu_scene.emitters.size());
        } else if (record.kind == EmitterKind::kTriangle) {
            emitter.position = Vec4(record.p0, gpu::kEmitterTriangle);
            emitter.edge1 = Vec4(record.edge1, record.area);
            emitter.edge2 = Vec4(record.edge2);
            emitter.direction = Vec4(record.normal, record.two_sided ? 1.0f : 0.0f);
            emitter.radiance = Vec4(record.radiance);
            emitter.texture = {record.uv0.x, record.uv0.y, std::bit_cast<float>(record.texture),
                               0.0f};
            emitter.uv_edges = {record.uv_edge1.x, record.uv_edge1.y, record.uv_edge2.x,
                                record.uv_edge2.y};
        } else {
            const PunctualLight& light = scene.lights[record.light];
            emitter.position = Vec4(light.position);
            emitter.direction = Vec4(light.direction);
            emitter.radiance = Vec4(light.intensity, light.range);
            emitter.cone = {light.cos_inner, light.cos_outer,
                            1.0f / std::max(0.001f, light.cos_inner - light.cos_outer),
                            light.smooth_falloff ? 1.0f : 0.0f};
            uint32_t kind = gpu::kEmitterPoint;
            switch (light.type) {
                case LightType::kPoint:
                    break;
                case LightType::kSpot:
                    kind = gpu::kEmitterSpot;
                    break;
                case LightType::kDirectional:
                    kind = gpu::kEmitterDirectional;
                    break;
                case LightType::kGoniometric:
                case LightType::kProjection:
                    break;  // refused by BuildGpuScene
            }
            emitter.position.w = std::bit_cast<float>(kind);
        }
        emitter.power = Vec4(record.power, inverse_probability);
        // An environment photon carries L / pdf x pi r^2, and the pdf follows the channels'
        // average: a channel reaches 3x the average power where a texel is one pure colour.
        const float most = record.kind == EmitterKind::kEnvironment
                               ? 3 * Average(record.power)
                               : MaxComponent(record.power) * record.peak;
        gpu_scene.max_photon_flux = std::max(gpu_scene.max_photon_flux, most * inverse_probability);
        gpu_scene.emitters.push_back(emitter);
        cumulative += record.probability;
        gpu_scene.emitter_cdf.push_back(static_cast<float>(cumulative));
    }
    // Rounding must not leave a u in [0, 1) past the last emitter.
    if (!gpu_scene.emitter_cdf.empty()) gpu_scene.emitter_cdf.back() = 2.0f;
}

}  // namespace

SpecConstants SpecConstantsFor(const SceneFeatures& features) {
    SpecConstants spec{};
    spec[gpu::kSpecHasMirror] = features.mirror;
    spec[gpu::kSpecHasDielectric] = features.dielectric;
    spec[gpu::kSpecHasThinDielectric] = features.thin_dielectric;
    spec[gpu::kSpecHasTextures] = features.textures;
    spec[gpu::kSpecHasSmoothNormals] = features.smooth_normals;
    spec[gpu::kSpecHasTriangleLights] = features.triangle_lights;
    spec[gpu::kSpecHasPointLights] = features.point_lights;
    spec[gpu::kSpecHasSpotLights] = features.spot_lights;
    spec[gpu::kSpecHasDirectionalLights] = features.directional_lights;
    spec[gpu::kSpecHasRoughConductor] = features.rough_conductor;
    spec[gpu::kSpecHasRoughDielectric] = features.rough_dielectric;
    spec[gpu::kSpecHasEnvironment] = features.environment;
    spec[gpu::kSpecHasTexturedLights] = features.textured_lights;
    return spec;
}

absl::StatusOr<GpuScene> BuildGpuScene(const Scene& job_scene, const Emitters& emitters) {
    GpuScene gpu_scene;
    gpu_scene.features = AnalyseFeatures(job_scene, emitters);
    if (gpu_scene.features.image_lights)
        return absl::UnimplementedError(
            "the Vulkan backend does not emit goniometric or projection lights yet; render "
            "this scene with --backend cpu");
    // The kernels traverse one BVH: instances are expanded into world triangles (the world's
    // own keep their indices, so emitters still name them).
    absl::StatusOr<Scene> flattened;
    if (!job_scene.instances.empty()) {
        flattened = FlattenInstances(job_scene, SceneLimits{}.max_triangles);
        if (!flattened.ok()) return flattened.status();
    }
    const Scene& scene = job_scene.instances.empty() ? job_scene : *flattened;
    std::vector<Bounds> boxes;
    for (const Triangle& triangle : scene.triangles) {
        Bounds box;
        for (uint32_t v : triangle.vertex) box.Extend(scene.positions[v]);
        boxes.push_back(box);
    }
    if (boxes.empty()) {
        // Nothing to hit: one empty box at the origin, over a degenerate triangle that no ray
        // intersects (its determinant is 0).
        boxes.push_back({Vec3(0.0f), Vec3(0.0f)});
    }
    absl::StatusOr<embree::GpuBvh> bvh = embree::BuildGpuBvh(boxes);
    if (!bvh.ok()) return bvh.status();
    gpu_scene.nodes = std::move(bvh->nodes);
    if (scene.triangles.empty()) {
        gpu_scene.triangles.push_back({Vec4(Vec3(0.0f), 0u), Vec4(Vec3(0.0f)), Vec4(Vec3(0.0f))});
        gpu_scene.shading.push_back({Vec4(Vec3(0, 0, 1), gpu::kNoEmitter), {0, 0, 0, 0}});
    } else {
        AddGeometry(scene, emitters, *bvh, gpu_scene);
    }
    AddEmitters(scene, emitters, gpu_scene);
    gpu_scene.sphere = Vec4(emitters.SceneCenter(), emitters.SceneRadius());
    gpu_scene.magnitude = scene.bounds.Magnitude();
    return gpu_scene;
}

}  // namespace pf::vk
