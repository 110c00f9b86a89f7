// Flattening a scene into the shared GPU structs.
#include "worker/backends/vulkan/gpu_scene.h"

#include <array>
#include <bit>

#include "core/scene/mesh_builder.h"
#include "core/shared/curve.h"
#include "core/shared/features.h"
#include "core/shared/noise.h"
#include "core/shared/sheen.h"
#include "embree/bvh_builder.h"

namespace pf::vk {
namespace {

gpu::vec4 Vec4(const Vec3& v, float w = 0) { return {v.x, v.y, v.z, w}; }
gpu::vec4 Vec4(const Vec3& v, uint32_t w_bits) {
    return {v.x, v.y, v.z, std::bit_cast<float>(w_bits)};
}

// The BVH's primitives are the triangles, then the curves (index - triangle count). A curve's
// leaf slot names its two records (gpu_types.h, GpuTriangle), which follow the slots.
void AddGeometry(const Scene& scene, const Emitters& emitters, const embree::GpuBvh& bvh,
                 GpuScene& gpu_scene) {
    const auto triangle_count = static_cast<uint32_t>(scene.triangles.size());
    const auto first_record = static_cast<uint32_t>(bvh.order.size());
    for (uint32_t t : bvh.order) {
        if (t >= triangle_count) {
            const uint32_t record = first_record + 2 * (t - triangle_count);
            gpu_scene.triangles.push_back(
                {Vec4(Vec3(0.0f), gpu::kCurveBit | record), Vec4(Vec3(0.0f)), Vec4(Vec3(0.0f))});
            continue;
        }
        const Triangle& triangle = scene.triangles[t];
        const Vec3& p0 = scene.positions[triangle.vertex[0]];
        const bool cut_out = scene.materials[triangle.material].HasCutOuts();
        gpu_scene.triangles.push_back(
            {Vec4(p0, t), Vec4(scene.positions[triangle.vertex[1]] - p0, cut_out ? 1.0f : 0.0f),
             Vec4(scene.positions[triangle.vertex[2]] - p0)});
    }
    for (uint32_t c = 0; c < scene.curves.size(); ++c) {
        const Curve& curve = scene.curves[c];
        const std::array<Vec3, 4>& p = curve.control;
        gpu_scene.triangles.push_back(
            {Vec4(p[0], curve.width[0]), Vec4(p[1], curve.width[1]), Vec4(p[2], curve.material)});
        gpu_scene.triangles.push_back({Vec4(p[3], static_cast<uint32_t>(curve.type)),
                                       Vec4(curve.normal[0], c), Vec4(curve.normal[1])});
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
    if (gpu_scene.shading.empty())  // curves alone: a placeholder no slot names
        gpu_scene.shading.push_back({Vec4(Vec3(0, 0, 1), gpu::kNoEmitter), {0, 0, 0, 0}});
    // What no kernel of this scene reads is neither built nor uploaded.
    if (gpu_scene.features.smooth_normals)
        for (const Vec3& normal : scene.normals) gpu_scene.normals.push_back(Vec4(normal));
    if (gpu_scene.features.ReadsUv())
        for (const Point2& uv : scene.uvs) gpu_scene.uvs.push_back({uv.x, uv.y});
    // Vertex colours share the tangents' binding: each after its vertex's tangent where the
    // scene has normal or bump maps (a zero tangent where it has none), else alone.
    if (gpu_scene.features.vertex_colors) {
        for (size_t v = 0; v < scene.positions.size(); ++v) {
            if (gpu_scene.features.shading_detail)
                gpu_scene.tangents.push_back(
                    Vec4(v < scene.tangents.size() ? scene.tangents[v] : Vec3(0.0f)));
            const VertexColor& color = scene.colors[v];
            gpu_scene.tangents.push_back(Vec4(color.rgb, color.alpha));
        }
    } else if (gpu_scene.features.shading_detail) {
        for (const Vec3& tangent : scene.tangents) gpu_scene.tangents.push_back(Vec4(tangent));
    }
    if (gpu_scene.features.sheen)
        gpu_scene.sheen_tables.assign(std::begin(gpu::kSheenTables), std::end(gpu::kSheenTables));
    for (const Material& material : scene.materials)
        gpu_scene.materials.push_back(
            {Vec4(material.base_color, material.ior), static_cast<uint32_t>(material.type),
             material.base_color_texture, material.roughness, material.roughness_texture,
             gpu::vec4{material.coat_ior, material.coat_roughness, material.coat_thickness,
                       std::bit_cast<float>(material.coat_depth)},
             gpu::vec4{std::bit_cast<float>(material.coat_kind), material.coat_weight,
                       std::bit_cast<float>(material.sheen_texture),
                       std::bit_cast<float>(material.sheen_roughness_texture)},
             gpu::vec4{material.alpha, material.alpha_cutoff,
                       std::bit_cast<float>(material.alpha_texture),
                       std::bit_cast<float>(material.surface_flags)},
             gpu::uvec4{material.mix_first, material.mix_second,
                        std::bit_cast<uint32_t>(material.mix_amount),
                        std::bit_cast<uint32_t>(material.mix_texture)},
             Vec4(material.conductor_eta, std::bit_cast<float>(material.conductor)),
             Vec4(material.conductor_k, std::bit_cast<float>(material.coat_samples)),
             Vec4(material.absorption, 0.0f),
             gpu::vec4{std::bit_cast<float>(material.normal_texture), material.normal_scale,
                       std::bit_cast<float>(material.bump_texture), material.bump_scale},
             Vec4(material.transmittance, std::bit_cast<float>(material.transmittance_texture)),
             Vec4(material.sheen_color, material.sheen_roughness),
             Vec4(material.outside_absorption, 0.0f)});
    if (!gpu_scene.features.ReadsUv() && !gpu_scene.features.textured_lights) return;
    // Procedural textures' noise reads Perlin's permutation from the first texels (noise.h).
    if (gpu_scene.features.procedural_textures)
        for (int32_t i = 0; i < gpu::kNoisePermutationSize; i += 4)
            gpu_scene.texels.push_back(
                {float(gpu::kNoisePermutation[i]), float(gpu::kNoisePermutation[i + 1]),
                 float(gpu::kNoisePermutation[i + 2]), float(gpu::kNoisePermutation[i + 3])});
    for (const std::shared_ptr<const Texture>& texture : scene.textures) {
        const auto first = static_cast<uint32_t>(gpu_scene.texels.size());
        if (texture->IsProcedural()) {  // its program, where the kernels can evaluate it
            gpu_scene.textures.push_back(
                {first, 0, static_cast<int32_t>(texture->program.size()), 0});
            gpu_scene.texels.insert(gpu_scene.texels.end(), texture->program.begin(),
                                    texture->program.end());
            continue;
        }
        gpu_scene.textures.push_back(
            {first, texture->width, texture->height, texture->wrap_u | (texture->wrap_v << 16)});
        for (const Rgb& texel : texture->texels) gpu_scene.texels.push_back(Vec4(texel));
    }
}

// Where an image's texels and sampling tables begin in the light-image bindings.
gpu::vec4 ImageOffsets(const GpuScene& gpu_scene, Point2 extent = {}) {
    return {std::bit_cast<float>(static_cast<uint32_t>(gpu_scene.light_image_texels.size())),
            std::bit_cast<float>(static_cast<uint32_t>(gpu_scene.light_image_tables.size())),
            extent.x, extent.y};
}

// The rotation from the world into an image's frame, a row each in edge2, direction and cone.
void SetImageRotation(const std::array<float, 9>& m, gpu::GpuEmitter& emitter) {
    emitter.edge2 = {m[0], m[1], m[2], 0.0f};
    emitter.direction = {m[3], m[4], m[5], 0.0f};
    emitter.cone = {m[6], m[7], m[8], 0.0f};
}

// An environment map, or a goniometric light's, with its sampling tables.
void AddEnvironmentMap(const Environment& environment, const EnvironmentSampler& sampler,
                       gpu::GpuEmitter& emitter, GpuScene& gpu_scene) {
    const auto bits = [](uint32_t value) { return std::bit_cast<float>(value); };
    emitter.edge1 = {bits(uint32_t(environment.image.width)),
                     bits(uint32_t(environment.image.height)),
                     bits(static_cast<uint32_t>(environment.mapping)), 0.0f};
    SetImageRotation(environment.to_map, emitter);
    emitter.radiance = Vec4(environment.scale);
    emitter.texture = ImageOffsets(gpu_scene);
    for (const Rgb& texel : environment.image.texels)
        gpu_scene.light_image_texels.push_back(Vec4(texel));
    for (const std::vector<float>* table :
         {&sampler.RowCdf(), &sampler.TexelCdf(), &sampler.TexelProbability()})
        gpu_scene.light_image_tables.insert(gpu_scene.light_image_tables.end(), table->begin(),
                                            table->end());
}

// A projection light's image, its texels' cumulative table and their probabilities.
void AddProjection(const PunctualLight& light, const Emitters::ImageSampler& sampler,
                   gpu::GpuEmitter& emitter, GpuScene& gpu_scene) {
    const Texture& image = *light.image;
    const auto bits = [](uint32_t value) { return std::bit_cast<float>(value); };
    emitter.edge1 = {bits(uint32_t(image.width)), bits(uint32_t(image.height)), 0.0f,
                     sampler.plane_texel_area};
    SetImageRotation(light.to_light, emitter);
    emitter.texture = ImageOffsets(gpu_scene, light.ProjectionExtent());
    for (const Rgb& texel : image.texels) gpu_scene.light_image_texels.push_back(Vec4(texel));
    std::vector<float>& tables = gpu_scene.light_image_tables;
    double cumulative = 0;
    tables.push_back(0.0f);
    for (uint32_t i = 0; i < image.texels.size(); ++i) {
        cumulative += sampler.texels.Probability(i);
        tables.push_back(static_cast<float>(cumulative));
    }
    tables.back() = 1.0f;
    for (uint32_t i = 0; i < image.texels.size(); ++i)
        tables.push_back(static_cast<float>(sampler.texels.Probability(i)));
}

void AddEmitters(const Scene& scene, const Emitters& emitters, GpuScene& gpu_scene) {
    double cumulative = 0;
    for (const Emitters::Record& record : emitters.Records()) {
        gpu::GpuEmitter emitter{};
        const auto inverse_probability = static_cast<float>(1.0 / record.probability);
        // The largest flux a photon of this emitter carries in a channel, before its pick.
        float most = MaxComponent(record.power) * record.peak;
        if (record.kind == EmitterKind::kEnvironment) {
            const Environment& environment = *scene.environment;
            emitter.position = Vec4(Vec3(0.0f), gpu::kEmitterEnvironment);
            AddEnvironmentMap(environment, emitters.EnvironmentSampling(), emitter, gpu_scene);
            gpu_scene.environment_emitter = static_cast<uint32_t>(gpu_scene.emitters.size());
            // A photon carries L / pdf x pi r^2, and the pdf follows the channels' average: a
            // channel reaches 3x the average power where a texel is one pure colour.
            most = 3 * Average(record.power);
            if (const std::optional<EnvironmentPortal>& portal = environment.portal) {
                const EnvironmentSampler& through = emitters.PortalSampling();
                emitter.position = Vec4(portal->corner, gpu::kEmitterEnvironment);
                emitter.portal_u = Vec4(portal->edge_u, portal->Area());
                emitter.portal_v = Vec4(portal->edge_v,
                                        static_cast<uint32_t>(gpu_scene.light_image_tables.size()));
                for (const std::vector<float>* table :
                     {&through.RowCdf(), &through.TexelCdf(), &through.TexelProbability()})
                    gpu_scene.light_image_tables.insert(gpu_scene.light_image_tables.end(),
                                                        table->begin(), table->end());
                // A photon carries L cos / pdf x the portal's area (with a margin for the
                // pdf's rounding in float).
                most = 1.001f * through.FacingFluxBound() * portal->Area();
            }
        } else if (record.kind == EmitterKind::kTriangle) {
            emitter.position = Vec4(record.p0, gpu::kEmitterTriangle);
            emitter.edge1 = Vec4(record.edge1, record.area);
            emitter.edge2 = Vec4(record.edge2, record.invisible ? 1.0f : 0.0f);
            emitter.direction = Vec4(record.normal, record.two_sided ? 1.0f : 0.0f);
            emitter.radiance = Vec4(record.radiance);
            emitter.texture = {record.uv0.x, record.uv0.y, std::bit_cast<float>(record.texture),
                               std::bit_cast<float>(record.colored_triangle < 0
                                                        ? gpu::kNoEmitter
                                                        : uint32_t(record.colored_triangle))};
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
                case LightType::kGoniometric: {
                    kind = gpu::kEmitterGoniometric;
                    const Emitters::ImageSampler& sampler = emitters.ImageSampling(record.light);
                    AddEnvironmentMap(*sampler.environment, sampler.directions, emitter, gpu_scene);
                    most = 3 * Average(record.power);  // as an environment's
                    break;
                }
                case LightType::kProjection: {
                    kind = gpu::kEmitterProjection;
                    AddProjection(light, emitters.ImageSampling(record.light), emitter, gpu_scene);
                    emitter.radiance = Vec4(light.intensity);
                    // The texels' pdf follows their channels' average and the cosine cubed at
                    // their centres, which a point of a corner texel may exceed by up to the
                    // corner's 1 / cos^3.
                    const Point2 extent = light.ProjectionExtent();
                    const float corner = 1 + extent.x * extent.x + extent.y * extent.y;
                    most = 3 * Average(record.power) * corner * std::sqrt(corner);
                    break;
                }
            }
            emitter.position.w = std::bit_cast<float>(kind);
        }
        emitter.power = Vec4(record.power, inverse_probability);
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
    spec[gpu::kSpecNearest] = 1;  // a heap of one where the job has none (pixel_trace.comp)
#define PF_SPECIALISE(name, id, member) spec[gpu::id] = features.member;
    PF_SCENE_FEATURES(PF_SPECIALISE)
#undef PF_SPECIALISE
    return spec;
}

absl::StatusOr<GpuScene> BuildGpuScene(const Scene& job_scene, const Emitters& emitters) {
    GpuScene gpu_scene;
    gpu_scene.features = AnalyseFeatures(job_scene, emitters);
    // The kernels traverse one BVH: instances are expanded into world triangles and curves (the
    // world's own keep their indices, so emitters still name them).
    absl::StatusOr<Scene> flattened;
    if (!job_scene.instances.empty()) {
        flattened =
            FlattenInstances(job_scene, SceneLimits{}.max_triangles, SceneLimits{}.max_curves);
        if (!flattened.ok()) return flattened.status();
    }
    const Scene& scene = job_scene.instances.empty() ? job_scene : *flattened;
    std::vector<Bounds> boxes;
    for (const Triangle& triangle : scene.triangles) {
        Bounds box;
        for (uint32_t v : triangle.vertex) box.Extend(scene.positions[v]);
        boxes.push_back(box);
    }
    for (const Curve& curve : scene.curves) boxes.push_back(curve.Box());
    if (boxes.empty()) {
        // Nothing to hit: one empty box at the origin, over a degenerate triangle that no ray
        // intersects (its determinant is 0).
        boxes.push_back({Vec3(0.0f), Vec3(0.0f)});
    }
    absl::StatusOr<embree::GpuBvh> bvh = embree::BuildGpuBvh(boxes);
    if (!bvh.ok()) return bvh.status();
    gpu_scene.nodes = std::move(bvh->nodes);
    if (scene.triangles.empty() && scene.curves.empty()) {
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
