// Photon emission and direct-light sampling over all of a scene's emitters.
#include "core/scene/emitters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "core/sampling/frame.h"
#include "core/sampling/sampling.h"

namespace pf {
namespace {

float SpotSolidAngle(const PunctualLight& light) { return 2.0f * kPi * (1.0f - light.cos_outer); }

// The mean of a texture's bilinear lookups over the triangle uv0 + b1 edge1 + b2 edge2 of
// texture space, each times the vertex colours `colors` interpolated there: at the centroids of
// its subdivision into n^2 equal triangles, n growing with the texels it covers (up to 64,
// 4096 lookups).
Rgbd MeanOverTriangle(const Texture& texture, Point2 uv0, Point2 edge1, Point2 edge2,
                      const std::array<Rgb, 3>& colors) {
    const double texels = 0.5 * std::abs(double(edge1.x) * edge2.y - double(edge1.y) * edge2.x) *
                          texture.width * texture.height;
    const int n = static_cast<int>(std::clamp(std::ceil(std::sqrt(texels)), 1.0, 64.0));
    Rgbd sum;
    const auto add = [&](double b1, double b2) {
        const Rgbd color =
            Rgbd(colors[0]) * (1 - b1 - b2) + Rgbd(colors[1]) * b1 + Rgbd(colors[2]) * b2;
        sum +=
            color * Rgbd(texture.Sample(static_cast<float>(uv0.x + edge1.x * b1 + edge2.x * b2),
                                        static_cast<float>(uv0.y + edge1.y * b1 + edge2.y * b2)));
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            add((i + 1.0 / 3) / n, (j + 1.0 / 3) / n);  // the corner (i, j) points up
            if (i + j + 1 < n) add((i + 2.0 / 3) / n, (j + 2.0 / 3) / n);  // and down
        }
    return sum * (1.0 / (double(n) * n));
}

float LargestTexel(const Texture& texture) {
    float largest = 0;
    for (const Rgb& texel : texture.texels) largest = std::max(largest, MaxComponent(texel));
    return largest;
}

}  // namespace

std::vector<Emitters::Record> Emitters::Records() const {
    std::vector<Record> records;
    records.reserve(emitters_.size());
    // Each emission texture's largest texel, found once: a textured light is thousands of
    // triangles over one texture of millions of texels (StainedGlassLamp: 16.7M).
    std::unordered_map<const Texture*, float> largest_texel;
    for (uint32_t i = 0; i < emitters_.size(); ++i) {
        Record record;
        record.kind = emitters_[i].kind;
        record.power = emitters_[i].power;
        record.probability = distribution_.Probability(i);
        if (record.kind == EmitterKind::kTriangle) {
            const EmissiveTriangle& triangle = triangles_[emitters_[i].index];
            record.p0 = triangle.p0, record.edge1 = triangle.edge1, record.edge2 = triangle.edge2;
            record.normal = triangle.frame.n, record.radiance = triangle.radiance,
            record.area = triangle.area, record.two_sided = triangle.two_sided;
            record.invisible = triangle.invisible;
            if (triangle.texture != nullptr) {
                record.texture = triangle.texture_index;
                record.uv0 = triangle.uv0, record.uv_edge1 = triangle.uv_edge1,
                record.uv_edge2 = triangle.uv_edge2;
                const auto [found, inserted] = largest_texel.try_emplace(triangle.texture, 0.0f);
                if (inserted) found->second = LargestTexel(*triangle.texture);
                record.peak = found->second;
            }
            if (triangle.colored) record.colored_triangle = static_cast<int32_t>(triangle.triangle);
            // A photon's flux varies with where it leaves: the power before that (colours lie
            // in [0, 1], so they raise no peak).
            if (triangle.texture != nullptr || triangle.colored)
                record.power =
                    triangle.radiance * ((triangle.two_sided ? 2.0f : 1.0f) * kPi * triangle.area);
        } else if (record.kind == EmitterKind::kPunctual) {
            record.light = emitters_[i].index;
        }
        records.push_back(record);
    }
    return records;
}

Emitters::Emitters(const Scene& scene) : scene_(scene) {
    scene_center_ = scene.bounds.Center();
    scene_radius_ = std::max(0.5f * scene.bounds.Diagonal(), 1e-30f);
    std::vector<double> weights;
    emitter_of_triangle_.assign(scene.WorldTriangleCount(), -1);
    auto add = [&](EmitterKind kind, uint32_t index, const Rgbd& power) {
        if (!(Average(power) > 0) || !IsFinite(power)) return false;
        emitters_.push_back({kind, index, Rgb(power)});
        weights.push_back(Average(power));
        power_rgb_ += power;
        return true;
    };
    for (uint32_t t = 0; t < scene.WorldTriangleCount(); ++t) {  // prototypes hold no emitters
        const Material& material = scene.materials[scene.triangles[t].material];
        if (!material.IsEmissive()) continue;
        const Triangle& triangle = scene.triangles[t];
        const Vec3& p0 = scene.positions[triangle.vertex[0]];
        const Vec3 edge1 = scene.positions[triangle.vertex[1]] - p0,
                   edge2 = scene.positions[triangle.vertex[2]] - p0;
        const auto index = static_cast<uint32_t>(triangles_.size());
        EmissiveTriangle emissive{p0,
                                  edge1,
                                  edge2,
                                  FrameFromNormal(triangle.normal),
                                  material.emission,
                                  scene.TriangleArea(t),
                                  material.two_sided != 0};
        if (material.emission_texture != kNoTexture) {
            emissive.texture = scene.textures[material.emission_texture].get();
            emissive.texture_index = material.emission_texture;
            const Point2& uv0 = scene.uvs[triangle.vertex[0]];
            const Point2 &uv1 = scene.uvs[triangle.vertex[1]], &uv2 = scene.uvs[triangle.vertex[2]];
            emissive.uv0 = uv0;
            emissive.uv_edge1 = {uv1.x - uv0.x, uv1.y - uv0.y};
            emissive.uv_edge2 = {uv2.x - uv0.x, uv2.y - uv0.y};
        }
        emissive.invisible = material.alpha <= 0 && material.alpha_texture == kNoTexture;
        if ((material.surface_flags & gpu::kSurfaceVertexEmission) != 0 && !scene.colors.empty()) {
            for (int k = 0; k < 3; ++k) emissive.colors[k] = scene.colors[triangle.vertex[k]].rgb;
            emissive.colored = std::any_of(emissive.colors.begin(), emissive.colors.end(),
                                           [](const Rgb& c) { return !(c == Rgb(1.0f)); });
            emissive.triangle = t;
        }
        triangles_.push_back(emissive);
        if (add(EmitterKind::kTriangle, index, emissive.Power()))
            emitter_of_triangle_[t] = static_cast<int32_t>(emitters_.size() - 1);
    }
    for (uint32_t l = 0; l < scene.lights.size(); ++l) {
        const PunctualLight& light = scene.lights[l];
        const Rgbd intensity(light.intensity);
        switch (light.type) {
            case LightType::kPoint:
                add(EmitterKind::kPunctual, l, intensity * (4.0 * kPiD));
                break;
            case LightType::kSpot:
                add(EmitterKind::kPunctual, l, intensity * double(SpotSolidAngle(light)));
                break;
            case LightType::kDirectional:
                add(EmitterKind::kPunctual, l, intensity * (kPiD * scene_radius_ * scene_radius_));
                break;
            case LightType::kGoniometric:
            case LightType::kProjection:
                image_samplers_.resize(scene.lights.size());
                image_samplers_[l] = MakeImageSampler(light);
                add(EmitterKind::kPunctual, l, image_samplers_[l].power);
                break;
        }
    }
    if (scene.environment) {
        const Environment& environment = *scene.environment;
        // Power through a disk as wide as the scene, facing each direction: pi R^2 x the
        // radiance's integral over the sphere; through a portal: its area x the irradiance on
        // it from outside.
        const double disk = kPiD * double(scene_radius_) * double(scene_radius_);
        const Rgbd power = environment.portal ? environment.Irradiance(environment.portal->normal) *
                                                    double(environment.portal->Area())
                                              : environment.RadianceIntegral() * disk;
        if (add(EmitterKind::kEnvironment, 0, power)) {
            environment_emitter_ = static_cast<int32_t>(emitters_.size() - 1);
            environment_sampler_ = EnvironmentSampler(environment);
            if (environment.portal)
                portal_sampler_ = EnvironmentSampler(environment, environment.portal->normal);
        }
    }
    if (weights.empty()) return;
    distribution_ = DiscreteDistribution(weights);
    total_power_ = distribution_.Total();
    for (uint32_t i = 0; i < emitters_.size(); ++i)
        inverse_probability_.push_back(static_cast<float>(1.0 / distribution_.Probability(i)));
}

EmittedPhoton Emitters::Emit(const EmissionNumbers& numbers) const {
    const auto pick = distribution_.Draw(numbers.u[0]);
    const Emitter& emitter = emitters_[pick.index];
    const float* u = numbers.u.data() + 1;
    EmittedPhoton photon;
    switch (emitter.kind) {
        case EmitterKind::kTriangle:
            photon = EmitFromTriangle(triangles_[emitter.index], u);
            break;
        case EmitterKind::kPunctual:
            photon = EmitFromLight(scene_.lights[emitter.index], emitter.index, u);
            break;
        case EmitterKind::kEnvironment:
            photon = EmitFromEnvironment(u);
            break;
    }
    photon.flux *= inverse_probability_[pick.index];
    return photon;
}

Rgbd Emitters::EmissiveTriangle::Power() const {
    const double sides = two_sided ? 2.0 : 1.0;
    const Rgbd power = Rgbd(radiance) * (sides * kPiD * area);
    const std::array<Rgb, 3> white{Rgb(1.0f), Rgb(1.0f), Rgb(1.0f)};
    if (texture != nullptr)
        return power *
               MeanOverTriangle(*texture, uv0, uv_edge1, uv_edge2, colored ? colors : white);
    if (!colored) return power;
    // The mean of a linear function over a triangle: its value at the centroid.
    return power * ((Rgbd(colors[0]) + Rgbd(colors[1]) + Rgbd(colors[2])) * (1.0 / 3));
}

EmittedPhoton Emitters::EmitFromTriangle(const EmissiveTriangle& triangle, const float* u) const {
    const Point2 b = SampleUniformTriangle(u[0], u[1]);
    const Vec3 point = triangle.p0 + triangle.edge1 * b.x + triangle.edge2 * b.y;
    // A two-sided light leaves from either face with equal chance.
    const bool back = triangle.two_sided && u[2] < 0.5f;
    Vec3 direction = ToWorld(triangle.frame, SampleCosineHemisphere(u[3], u[4]));
    if (back) direction = -direction;
    const Vec3 normal = back ? -triangle.frame.n : triangle.frame.n;
    // Cosine-weighted emission of radiance Le from area A carries flux pi * A * Le a side.
    return {
        {OffsetRayOrigin(point, normal, scene_.bounds.Magnitude()), direction},
        triangle.RadianceAt(b.x, b.y) * ((triangle.two_sided ? 2.0f : 1.0f) * kPi * triangle.area)};
}

Emitters::ImageSampler Emitters::MakeImageSampler(const PunctualLight& light) {
    ImageSampler sampler;
    const Texture& image = *light.image;
    if (light.type == LightType::kGoniometric) {
        auto environment = std::make_shared<Environment>();
        environment->mapping = EnvironmentMapping::kEqualArea;
        environment->scale = light.intensity;
        environment->image = image;
        environment->to_map = light.to_light;
        sampler.environment = environment;
        sampler.directions = EnvironmentSampler(*environment);
        sampler.power = environment->RadianceIntegral();
        return sampler;
    }
    // Projection: texel (x, y) spans solid angle ~ its plane area x cos^3 at its centre.
    const Point2 extent = light.ProjectionExtent();
    sampler.plane_texel_area =
        static_cast<float>(4.0 * extent.x * extent.y / (double(image.width) * image.height));
    std::vector<double> weights(image.texels.size());
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double cosine = 1 / Length(Vec3d(light.ProjectionPlanePoint(x + 0.5f, y + 0.5f)));
            const Rgbd texel(image.texels[size_t(y) * image.width + x]);
            const double solid_angle = sampler.plane_texel_area * cosine * cosine * cosine;
            weights[size_t(y) * image.width + x] = Average(texel) * solid_angle;
            sampler.power += texel * solid_angle;
        }
    sampler.power = sampler.power * Rgbd(light.intensity);
    if (Average(sampler.power) > 0) sampler.texels = DiscreteDistribution(weights);
    return sampler;
}

EmittedPhoton Emitters::EmitFromImageLight(const PunctualLight& light, const ImageSampler& sampler,
                                           const float* u) const {
    const float u1 = u[0], u2 = u[1];
    if (light.type == LightType::kGoniometric) {
        const EnvironmentSampler::Sample drawn = sampler.directions.Draw(u1, u2);
        if (!(drawn.pdf > 0)) return {{light.position, drawn.toward}, Rgb(0.0f)};
        return {{light.position, drawn.toward}, drawn.radiance / drawn.pdf};
    }
    // Projection: a texel by its share of the power, then a point of it on the plane z = 1.
    const Texture& image = *light.image;
    const DiscreteDistribution::Sample pick = sampler.texels.Draw(u1);
    const int x = static_cast<int>(pick.index % uint32_t(image.width));
    const int y = static_cast<int>(pick.index / uint32_t(image.width));
    const Vec3 local = Normalize(light.ProjectionPlanePoint(x + u2, y + u[2]));
    const float* m = light.to_light.data();  // its transpose takes the light's frame to the world
    const Vec3 toward = Normalize(Vec3(m[0] * local.x + m[3] * local.y + m[6] * local.z,
                                       m[1] * local.x + m[4] * local.y + m[7] * local.z,
                                       m[2] * local.x + m[5] * local.y + m[8] * local.z));
    // The density in solid angle: the texel's probability over its plane area, times the
    // plane's dA / d(omega) = 1 / cos^3.
    const float cosine = local.z;
    const auto pdf = static_cast<float>(pick.probability / sampler.plane_texel_area) /
                     (cosine * cosine * cosine);
    const Rgb texel = image.texels[pick.index];
    return {{light.position, toward}, light.intensity * texel / pdf};
}

EmittedPhoton Emitters::EmitFromLight(const PunctualLight& light, uint32_t index,
                                      const float* u) const {
    if (light.HasImage()) return EmitFromImageLight(light, image_samplers_[index], u);
    const float u1 = u[0], u2 = u[1];
    switch (light.type) {
        case LightType::kPoint:
            return {{light.position, SampleUniformSphere(u1, u2)},
                    light.intensity * (4.0f * kPi),
                    light.range > 0 ? &light : nullptr};
        case LightType::kSpot: {
            const Vec3 local = SampleUniformCone(u1, u2, light.cos_outer);
            const Vec3 direction = ToWorld(FrameFromNormal(light.direction), local);
            return {{light.position, direction},
                    light.intensity * (light.SpotFalloff(local.z) * SpotSolidAngle(light)),
                    light.range > 0 ? &light : nullptr};
        }
        case LightType::kDirectional: {
            // A disk as wide as the scene's bounding sphere, just outside it, facing the light.
            const Frame frame = FrameFromNormal(light.direction);
            const Point2 d = SampleUniformDisk(u1, u2);
            const Vec3 origin = scene_center_ - light.direction * (1.01f * scene_radius_) +
                                (frame.s * d.x + frame.t * d.y) * scene_radius_;
            return {{origin, light.direction},
                    light.intensity * (kPi * scene_radius_ * scene_radius_)};
        }
        case LightType::kGoniometric:
        case LightType::kProjection:
            break;  // EmitFromImageLight
    }
    return {};
}

EmittedPhoton Emitters::EmitFromEnvironment(const float* u) const {
    const float u1 = u[0], u2 = u[1];
    if (const std::optional<EnvironmentPortal>& portal = scene_.environment->portal) {
        // Through the portal: a direction drawn over the hemisphere outside it, then a point
        // of it, uniform: flux L cos / pdf x its area (pbrt-v4's SampleLe keeps the disk, but
        // only what comes through the portal lights the scene).
        const EnvironmentSampler::Sample sample = portal_sampler_.Draw(u1, u2);
        const float a = u[2], b = u[3];
        const Vec3 point = portal->corner + portal->edge_u * a + portal->edge_v * b;
        const Vec3 origin = OffsetRayOrigin(point, portal->normal, SceneScale());
        const float cosine = Dot(sample.toward, portal->normal);
        if (!(sample.pdf > 0) || !(cosine > 0)) return {{origin, -sample.toward}, Rgb(0.0f)};
        return {{origin, -sample.toward}, sample.radiance * (cosine * portal->Area() / sample.pdf)};
    }
    // A direction drawn from the map, then a point on the disk of the scene's bounding sphere
    // facing it, just outside: flux L / pdf x pi R^2 (pbrt-v4's ImageInfiniteLight::SampleLe).
    const EnvironmentSampler::Sample sample = environment_sampler_.Draw(u1, u2);
    if (!(sample.pdf > 0)) return {{scene_center_, -sample.toward}, Rgb(0.0f)};
    const Frame frame = FrameFromNormal(sample.toward);
    const Point2 d = SampleUniformDisk(u[2], u[3]);
    const Vec3 origin = scene_center_ + sample.toward * (1.01f * scene_radius_) +
                        (frame.s * d.x + frame.t * d.y) * scene_radius_;
    return {{origin, -sample.toward},
            sample.radiance * (kPi * scene_radius_ * scene_radius_ / sample.pdf)};
}

bool Emitters::SampleDirect(const Vec3& p, const Vec3& n, Rng& rng, LightSample* sample) const {
    const float pick = rng.NextFloat();
    const float u1 = rng.NextFloat();
    const float u2 = rng.NextFloat();
    return SampleDirect(p, n, pick, Point2{u1, u2}, sample);
}

bool Emitters::SampleDirect(const Vec3& p, const Vec3& n, float pick_u, Point2 u,
                            LightSample* sample, bool pick_from_u) const {
    const auto pick = distribution_.Draw(pick_from_u ? u.x : pick_u);
    const Emitter& emitter = emitters_[pick.index];
    const float u1 = pick_from_u ? distribution_.Remap(u.x, pick.index) : u.x, u2 = u.y;
    const Vec3 origin = OffsetRayOrigin(p, n, SceneScale());
    Vec3 to_light;
    float distance = std::numeric_limits<float>::infinity();
    Rgb radiance_over_pdf;
    if (emitter.kind == EmitterKind::kEnvironment && scene_.environment->portal) {
        // A point of the portal, uniform: area pdf 1/A, in solid angle d^2 / (cos A).
        const EnvironmentPortal& portal = *scene_.environment->portal;
        to_light = portal.corner + portal.edge_u * u1 + portal.edge_v * u2 - origin;
        const float distance_sq = LengthSquared(to_light);
        to_light /= std::sqrt(distance_sq);
        const float cosine = Dot(to_light, portal.normal);
        if (!(cosine > 0) || !(distance_sq > 0)) return false;
        radiance_over_pdf =
            scene_.environment->Radiance(to_light) * (cosine * portal.Area() / distance_sq);
        sample->pdf = static_cast<float>(distribution_.Probability(pick.index)) * distance_sq /
                      (cosine * portal.Area());
    } else if (emitter.kind == EmitterKind::kEnvironment) {
        const EnvironmentSampler::Sample drawn = environment_sampler_.Draw(u1, u2);
        if (!(drawn.pdf > 0)) return false;
        to_light = drawn.toward;
        radiance_over_pdf = drawn.radiance / drawn.pdf;
        sample->pdf = static_cast<float>(distribution_.Probability(pick.index)) * drawn.pdf;
    } else if (emitter.kind == EmitterKind::kTriangle) {
        const EmissiveTriangle& triangle = triangles_[emitter.index];
        const Point2 b = SampleUniformTriangle(u1, u2);
        const Vec3 point = triangle.p0 + triangle.edge1 * b.x + triangle.edge2 * b.y;
        to_light = point - origin;
        const float distance_sq = LengthSquared(to_light);
        distance = std::sqrt(distance_sq);
        to_light /= distance;
        const float cos_light = triangle.CosineToward(to_light);
        if (!(cos_light > 0) || !(distance_sq > 0)) return false;
        // Area pdf 1/A converted to solid angle: d^2 / (cos_light A).
        radiance_over_pdf =
            triangle.RadianceAt(b.x, b.y) * (cos_light * triangle.area / distance_sq);
        sample->pdf = triangle.invisible
                          ? 0.0f
                          : static_cast<float>(distribution_.Probability(pick.index)) *
                                distance_sq / (cos_light * triangle.area);
    } else {
        const PunctualLight& light = scene_.lights[emitter.index];
        sample->pdf = 0;
        if (light.type == LightType::kDirectional) {
            to_light = -light.direction;
            radiance_over_pdf = light.intensity;
        } else {
            to_light = light.position - origin;
            const float distance_sq = LengthSquared(to_light);
            distance = std::sqrt(distance_sq);
            to_light /= distance;
            if (!(distance_sq > 0)) return false;
            float falloff = 1.0f;
            if (light.type == LightType::kSpot)
                falloff = light.SpotFalloff(-Dot(to_light, light.direction));
            radiance_over_pdf =
                light.intensity * (falloff * light.RangeWindow(distance) / distance_sq);
            if (light.HasImage()) radiance_over_pdf *= light.ImageFactor(-to_light);
        }
    }
    if (!(Dot(to_light, n) > 0) || IsBlack(radiance_over_pdf)) return false;
    sample->direction = to_light;
    // Stop short of the light itself by a relative margin, which scales with the scene (an
    // environment or a distant light is never reached: the ray runs on to infinity).
    sample->shadow_ray = {origin, to_light, distance * (1.0f - 1e-4f)};
    sample->radiance_over_pdf = radiance_over_pdf * inverse_probability_[pick.index];
    return true;
}

Emitters::Hit Emitters::Escaped(const Vec3& origin, const Vec3& toward) const {
    if (environment_emitter_ < 0) return {};
    const auto pick = static_cast<float>(distribution_.Probability(uint32_t(environment_emitter_)));
    if (const std::optional<EnvironmentPortal>& portal = scene_.environment->portal) {
        const std::optional<float> exit = portal->Exit(origin, toward);
        if (!exit) return {};
        const float cosine = Dot(toward, portal->normal);
        return {scene_.environment->Radiance(toward),
                pick * *exit * *exit / (cosine * portal->Area())};
    }
    return {scene_.environment->Radiance(toward), pick * environment_sampler_.Pdf(toward)};
}

float Emitters::PdfDirect(uint32_t triangle, const Vec3& p, const Vec3& on_light) const {
    const int32_t emitter = EmitterOfTriangle(triangle);
    if (emitter < 0) return 0;
    const auto index = static_cast<uint32_t>(emitter);
    const EmissiveTriangle& emissive = triangles_[emitters_[index].index];
    const Vec3 to_light = on_light - p;
    const float distance_sq = LengthSquared(to_light);
    const float cos_light = emissive.CosineToward(to_light / std::sqrt(distance_sq));
    if (!(cos_light > 0) || !(distance_sq > 0)) return 0;
    return static_cast<float>(distribution_.Probability(index)) * distance_sq /
           (cos_light * emissive.area);
}

Emitters::Hit Emitters::HitEmitter(const RayHit& hit, const Vec3& p, const Vec3& on_light) const {
    const float pdf = PdfDirect(hit.triangle, p, on_light);
    if (!(pdf > 0)) return {};
    const EmissiveTriangle& emissive = triangles_[emitters_[EmitterOfTriangle(hit.triangle)].index];
    return {emissive.RadianceAt(hit.b1, hit.b2), pdf};
}

}  // namespace pf
