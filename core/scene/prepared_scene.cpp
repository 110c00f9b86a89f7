// The prepared scene's binary form: a header (magic, version, payload size, the payload's
// SHA-256), then the payload written with ByteWriter, arrays of plain fields (no struct
// padding ever reaches the bytes, so equal scenes give equal bytes).
#include "core/scene/prepared_scene.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/scene/pixel_filter.h"
#include "core/scene/texture_filter.h"
#include "core/scene/texture_program.h"
#include "core/shared/coat.h"
#include "core/util/byte_stream.h"
#include "core/util/sha256.h"

namespace pf {
namespace {

constexpr char kMagic[8] = {'P', 'F', 'S', 'C', 'E', 'N', 'E', '\0'};
constexpr size_t kDigestBytes = 64;  // hex SHA-256
constexpr size_t kHeaderBytes = sizeof(kMagic) + 4 + 8 + kDigestBytes;
// Far above any scene the coordinator accepts (SceneLimits), far below what would overflow.
constexpr uint64_t kMaxCount = uint64_t{1} << 32;

// Types written whole must have no padding: their size is the sum of their fields'.
static_assert(sizeof(Vec3) == 12 && sizeof(Point2) == 8);
static_assert(sizeof(Material) == 220, "Material gained a field or padding: encode it");
static_assert(sizeof(VertexColor) == 16);
static_assert(sizeof(PixelFilter) == 4 + 6 * 4);
static_assert(sizeof(Camera) == 4 * 12 + 4 * 4 + 4 + sizeof(ScreenWindow) + 4 + sizeof(PixelFilter),
              "Camera gained a field or padding: encode it");
static_assert(sizeof(Prototype) == 16 + 24 && sizeof(Instance) == 4 + 21 * 4);
static_assert(sizeof(Curve) == 4 * 12 + 2 * 4 + 2 * 12 + 4 + 4,
              "Curve gained a field or padding: encode it");
static_assert(sizeof(Bounds) == 24 && sizeof(SceneRenderHints) == 16);

absl::Status Invalid(const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat("prepared scene: ", what));
}

bool Finite(float x) { return std::isfinite(x); }
bool Finite(const Vec3& v) { return IsFinite(v); }
bool Finite(const Point2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }
template <size_t N>
bool Finite(const std::array<float, N>& values) {
    return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

template <typename T>
void Write(ByteWriter& out, const std::vector<T>& values) {
    out.Array(std::span<const T>(values));
}

// A texture's texels, as a palette where they take at most 256 values (an 8-bit image decoded
// to linear floats takes 256 at most): the distinct values' bits in ascending order and a byte
// per channel, each stored as its difference from the same channel's previous texel (PNG's
// "Sub" filter: smooth images give small differences, which zstd packs as PNG's deflate does)
// -- a quarter of the floats, still every bit of them. Otherwise the floats.
enum class TexelEncoding : uint8_t { kFloats, kPalette };

void WriteTexture(const Texture& texture, ByteWriter& out) {
    out.Value<int32_t>(texture.width);
    out.Value<int32_t>(texture.height);
    out.Value<uint32_t>(texture.wrap_u);
    out.Value<uint32_t>(texture.wrap_v);
    std::vector<float> palette;
    for (const Rgb& texel : texture.texels) {
        for (int c = 0; c < 3; ++c) palette.push_back(texel[c]);
        if (palette.size() > 4096) {  // keep the sort small: dedupe as it grows
            std::sort(palette.begin(), palette.end());
            palette.erase(std::unique(palette.begin(), palette.end()), palette.end());
            if (palette.size() > 256) break;
        }
    }
    std::sort(palette.begin(), palette.end());
    palette.erase(std::unique(palette.begin(), palette.end()), palette.end());
    const bool finite =
        std::all_of(palette.begin(), palette.end(), [](float x) { return std::isfinite(x); });
    // -0 and +0 compare equal: a palette holds one, so images with both stay floats.
    const auto negative_zero = [](float x) { return x == 0.0f && std::signbit(x); };
    const bool signed_zeros =
        std::any_of(texture.texels.begin(), texture.texels.end(), [&](const Rgb& t) {
            return negative_zero(t.x) || negative_zero(t.y) || negative_zero(t.z);
        });
    Write(out, texture.program);
    if (palette.size() > 256 || !finite || signed_zeros) {
        out.Value(TexelEncoding::kFloats);
        Write(out, texture.texels);
        return;
    }
    std::vector<uint8_t> deltas(3 * texture.texels.size());
    uint8_t previous[3] = {0, 0, 0};
    for (size_t i = 0; i < texture.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const auto code = static_cast<uint8_t>(
                std::lower_bound(palette.begin(), palette.end(), texture.texels[i][c]) -
                palette.begin());
            deltas[3 * i + c] = static_cast<uint8_t>(code - previous[c]);
            previous[c] = code;
        }
    out.Value(TexelEncoding::kPalette);
    Write(out, palette);
    Write(out, deltas);
}

bool ReadTexture(ByteReader& in, Texture* texture) {
    TexelEncoding encoding{};
    if (!in.Value(&texture->width) || !in.Value(&texture->height) || !in.Value(&texture->wrap_u) ||
        !in.Value(&texture->wrap_v) || !in.Array(&texture->program, kMaxCount) ||
        !in.Value(&encoding) || texture->wrap_u > gpu::kWrapOctahedral ||
        texture->wrap_v > gpu::kWrapOctahedral)
        return false;
    if (encoding == TexelEncoding::kFloats) return in.Array(&texture->texels, kMaxCount);
    std::vector<float> palette;
    std::vector<uint8_t> deltas;
    if (encoding != TexelEncoding::kPalette || !in.Array(&palette, 256) ||
        !in.Array(&deltas, 3 * kMaxCount) || deltas.size() % 3 != 0)
        return false;
    texture->texels.resize(deltas.size() / 3);
    uint8_t code[3] = {0, 0, 0};
    for (size_t i = 0; i < texture->texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            code[c] = static_cast<uint8_t>(code[c] + deltas[3 * i + c]);
            if (code[c] >= palette.size()) return false;
            texture->texels[i][c] = palette[code[c]];
        }
    return true;
}

void WritePayload(const Scene& scene, ByteWriter& out) {
    const bool smooth = std::any_of(scene.triangles.begin(), scene.triangles.end(),
                                    [](const Triangle& t) { return t.smooth; });
    const bool textured = std::any_of(scene.materials.begin(), scene.materials.end(),
                                      [](const Material& m) { return m.ReadsUv(); });
    out.String(scene.source);
    Write(out, scene.positions);
    Write(out, smooth ? scene.normals : std::vector<Vec3>());
    Write(out, textured ? scene.uvs : std::vector<Point2>());
    Write(out, scene.tangents);
    Write(out, scene.colors);
    std::vector<uint32_t> vertices, materials;
    std::vector<uint8_t> smooth_flags;
    std::vector<Vec3> normals;
    for (const Triangle& t : scene.triangles) {
        vertices.insert(vertices.end(), t.vertex, t.vertex + 3);
        materials.push_back(t.material);
        smooth_flags.push_back(t.smooth ? 1 : 0);
        normals.push_back(t.normal);
    }
    Write(out, vertices), Write(out, materials), Write(out, smooth_flags), Write(out, normals);
    Write(out, scene.curves);
    Write(out, scene.prototypes);
    Write(out, scene.instances);
    Write(out, scene.materials);
    std::vector<bool> read(scene.textures.size(), false);
    const auto mark = [&](int32_t texture) {  // out of range: the decoder's to refuse
        if (texture >= 0 && size_t(texture) < read.size()) read[texture] = true;
    };
    for (const Material& m : scene.materials)
        for (const int32_t texture : m.Textures()) {
            mark(texture);
            // A procedural texture's images too.
            if (texture >= 0 && size_t(texture) < read.size() && scene.textures[texture])
                for (const size_t word : ProgramImageWords(scene.textures[texture]->program))
                    mark(std::bit_cast<int32_t>(scene.textures[texture]->program[word].y));
        }
    out.Value<uint64_t>(scene.textures.size());
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        const bool keep = read[t] && scene.textures[t] != nullptr;
        WriteTexture(keep ? *scene.textures[t] : Texture{}, out);
    }
    out.Value<uint64_t>(scene.lights.size());
    for (const PunctualLight& light : scene.lights) {
        out.Value(light.type), out.Value(light.position), out.Value(light.direction);
        out.Value(light.intensity), out.Value(light.cos_inner), out.Value(light.cos_outer);
        out.Value<uint8_t>(light.smooth_falloff ? 1 : 0);
        out.Value(light.range);
        out.Value(light.to_light), out.Value(light.tan_half_fov);
        out.Value<uint8_t>(light.image ? 1 : 0);
        if (light.image) WriteTexture(*light.image, out);
        out.String(light.name);
    }
    out.Value(scene.camera);
    out.Value(scene.bounds);
    out.Value(scene.hints);
    out.Value<uint8_t>(scene.environment ? 1 : 0);
    if (scene.environment) {
        const Environment& environment = *scene.environment;
        out.Value(environment.mapping), out.Value(environment.scale);
        out.Value(environment.to_map);
        out.String(environment.name);
        WriteTexture(environment.image, out);
        out.Value<uint8_t>(environment.portal ? 1 : 0);
        if (environment.portal) {
            const EnvironmentPortal& portal = *environment.portal;
            out.Value(std::array<Vec3, 4>{portal.corner, portal.corner + portal.edge_u,
                                          portal.corner + portal.edge_u + portal.edge_v,
                                          portal.corner + portal.edge_v});
        }
    }
}

// Reads every field; checks counts and bounds of what it reads, not the references between
// parts (CheckScene does).
absl::Status ReadPayload(ByteReader& in, Scene* scene) {
    const auto fail = [](const std::string& part) { return Invalid(part + " truncated"); };
    if (!in.String(&scene->source, 4096)) return fail("source");
    if (!in.Array(&scene->positions, kMaxCount)) return fail("positions");
    if (!in.Array(&scene->normals, kMaxCount)) return fail("normals");
    if (!in.Array(&scene->uvs, kMaxCount)) return fail("texture coordinates");
    if (!in.Array(&scene->tangents, kMaxCount)) return fail("tangents");
    if (!in.Array(&scene->colors, kMaxCount)) return fail("vertex colours");
    std::vector<uint32_t> vertices, materials;
    std::vector<uint8_t> smooth;
    std::vector<Vec3> normals;
    if (!in.Array(&vertices, kMaxCount * 3) || !in.Array(&materials, kMaxCount) ||
        !in.Array(&smooth, kMaxCount) || !in.Array(&normals, kMaxCount))
        return fail("triangles");
    const size_t count = materials.size();
    if (vertices.size() != 3 * count || smooth.size() != count || normals.size() != count)
        return Invalid("triangle arrays of different lengths");
    scene->triangles.resize(count);
    for (size_t t = 0; t < count; ++t) {
        Triangle& triangle = scene->triangles[t];
        std::copy_n(vertices.begin() + 3 * t, 3, triangle.vertex);
        triangle.material = materials[t];
        if (smooth[t] > 1)
            return Invalid(absl::StrCat("triangle ", t, ": smooth flag ", smooth[t]));
        triangle.smooth = smooth[t] == 1;
        triangle.normal = normals[t];
    }
    if (!in.Array(&scene->curves, kMaxCount)) return fail("curves");
    if (!in.Array(&scene->prototypes, kMaxCount)) return fail("prototypes");
    if (!in.Array(&scene->instances, kMaxCount)) return fail("instances");
    if (!in.Array(&scene->materials, kMaxCount)) return fail("materials");
    uint64_t textures = 0;
    if (!in.Value(&textures) || textures > kMaxCount) return fail("textures");
    for (uint64_t t = 0; t < textures; ++t) {
        auto texture = std::make_shared<Texture>();
        if (!ReadTexture(in, texture.get()))
            return Invalid(absl::StrCat("texture ", t, " truncated or its palette broken"));
        if (texture->width < 0 || texture->height < 0 ||
            uint64_t(texture->width) * uint64_t(texture->height) != texture->texels.size() ||
            (texture->IsProcedural() && !texture->texels.empty()))
            return Invalid(absl::StrCat("texture ", t, ": ", texture->width, "x", texture->height,
                                        " with ", texture->texels.size(), " texels"));
        scene->textures.push_back(std::move(texture));
    }
    // Procedural textures' programs, once every image they may read is known.
    for (size_t t = 0; t < scene->textures.size(); ++t)
        if (scene->textures[t]->IsProcedural())
            if (absl::Status status =
                    CheckTextureProgram(scene->textures[t]->program, scene->textures);
                !status.ok())
                return Invalid(absl::StrCat("texture ", t, ": ", status.message()));
    uint64_t lights = 0;
    if (!in.Value(&lights) || lights > kMaxCount) return fail("lights");
    for (uint64_t l = 0; l < lights; ++l) {
        PunctualLight light;
        uint8_t smooth_falloff = 0, has_image = 0;
        Texture image;
        if (!in.Value(&light.type) || !in.Value(&light.position) || !in.Value(&light.direction) ||
            !in.Value(&light.intensity) || !in.Value(&light.cos_inner) ||
            !in.Value(&light.cos_outer) || !in.Value(&smooth_falloff) || !in.Value(&light.range) ||
            !in.Value(&light.to_light) || !in.Value(&light.tan_half_fov) || !in.Value(&has_image) ||
            (has_image != 0 && !ReadTexture(in, &image)) || !in.String(&light.name, 4096))
            return fail(absl::StrCat("light ", l));
        light.smooth_falloff = smooth_falloff != 0;
        if (has_image != 0) {
            if (image.width <= 0 || image.height <= 0 ||
                uint64_t(image.width) * uint64_t(image.height) != image.texels.size())
                return Invalid(absl::StrCat("light ", l, ": its image's size is broken"));
            light.image = std::make_shared<const Texture>(std::move(image));
        }
        scene->lights.push_back(std::move(light));
    }
    if (!in.Value(&scene->camera) || !in.Value(&scene->bounds) || !in.Value(&scene->hints))
        return fail("camera");
    uint8_t has_environment = 0;
    if (!in.Value(&has_environment) || has_environment > 1) return fail("environment");
    if (has_environment == 1) {
        Environment& environment = scene->environment.emplace();
        if (!in.Value(&environment.mapping) || !in.Value(&environment.scale) ||
            !in.Value(&environment.to_map) || !in.String(&environment.name, 4096) ||
            !ReadTexture(in, &environment.image))
            return fail("environment");
        uint8_t has_portal = 0;
        if (!in.Value(&has_portal) || has_portal > 1) return fail("environment");
        if (has_portal == 1) {
            std::array<Vec3, 4> corners;
            if (!in.Value(&corners)) return fail("environment");
            absl::StatusOr<EnvironmentPortal> portal = EnvironmentPortal::FromCorners(corners);
            if (!portal.ok())
                return Invalid(
                    absl::StrCat("environment: its portal: ", portal.status().message()));
            environment.portal = *portal;
        }
    }
    if (!in.AtEnd()) return Invalid("bytes after the end");
    return absl::OkStatus();
}

absl::Status CheckMaterials(const Scene& scene) {
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        const std::string name = absl::StrCat("material ", m);
        if (static_cast<uint32_t>(material.type) > static_cast<uint32_t>(MaterialType::kMix))
            return Invalid(
                absl::StrCat(name, ": unknown type ", static_cast<uint32_t>(material.type)));
        if (!Finite(material.base_color) || !Finite(material.emission) || !Finite(material.ior) ||
            !Finite(material.roughness) || MinComponent(material.emission) < 0 ||
            !(material.ior > 0))
            return Invalid(absl::StrCat(name, ": a value out of range"));
        // A coat: an index of refraction above 1, roughness and thickness finite and
        // non-negative, on a base it can cover; or none (index 0).
        const bool coat_base = material.type == MaterialType::kDiffuse ||
                               material.type == MaterialType::kMirror ||
                               material.type == MaterialType::kRoughConductor;
        // A Fresnel mix covers a diffuse base only, with an F0 below 1 (an index below 1e3); no
        // coat but a sheen has index 1, so that a conductor's Fresnel term is its own.
        const bool coat_kind =
            material.coat_kind == gpu::kCoatLayered ||
            (material.coat_kind == gpu::kCoatFresnelMix &&
             material.type == MaterialType::kDiffuse && material.coat_ior < 1e3f) ||
            (material.coat_kind == gpu::kCoatNone && material.coat_ior == 1.0f);
        if (material.coat_ior != 0.0f &&
            !(material.coat_ior >= 1.0f && Finite(material.coat_ior) && coat_base && coat_kind &&
              material.coat_roughness >= 0.0f && material.coat_roughness <= 1.0f &&
              material.coat_thickness >= 0.0f && Finite(material.coat_thickness) &&
              material.coat_weight >= 0.0f && material.coat_weight <= 1.0f &&
              material.coat_depth <= 1024 && material.coat_samples >= 1 &&
              material.coat_samples <= 1024))
            return Invalid(absl::StrCat(name, ": a coat out of range"));
        // A sheen: a colour in [0, 1], over a coat (its layers' kinds carry it).
        if (!(Finite(material.sheen_color) && MinComponent(material.sheen_color) >= 0.0f &&
              MaxComponent(material.sheen_color) <= 1.0f && material.sheen_roughness >= 0.0f &&
              material.sheen_roughness <= 1.0f &&
              (material.HasCoat() || IsBlack(material.sheen_color))))
            return Invalid(absl::StrCat(name, ": a sheen out of range"));
        // A conductor Fresnel term of a known kind; a complex index as the loaders bound it.
        const auto in_range = [](const Rgb& v, float low) {
            return MinComponent(v) >= low && MaxComponent(v) < 1e4f;
        };
        if (!(material.conductor <= gpu::kConductorReflectance &&
              in_range(material.conductor_eta, 1e-30f) && in_range(material.conductor_k, 0.0f)))
            return Invalid(absl::StrCat(name, ": a conductor's Fresnel term out of range"));
        if (!(Finite(material.absorption) && MinComponent(material.absorption) >= 0 &&
              Finite(material.outside_absorption) &&
              MinComponent(material.outside_absorption) >= 0))
            return Invalid(absl::StrCat(name, ": absorption out of range"));
        if (!(Finite(material.transmittance) && MinComponent(material.transmittance) >= 0 &&
              (!material.IsTranslucent() ||
               (material.type == MaterialType::kDiffuse && !material.HasCoat()))))
            return Invalid(absl::StrCat(name, ": transmittance out of range"));
        if (!(Finite(material.normal_scale) && Finite(material.bump_scale)))
            return Invalid(absl::StrCat(name, ": a normal or bump map's scale not finite"));
        if (material.normal_texture != kNoTexture &&
            scene.tangents.size() != scene.positions.size())
            return Invalid(absl::StrCat(name, " has a normal map, the vertices no tangents"));
        // A mix's materials come before it: resolving one always ends.
        if (material.type == MaterialType::kMix &&
            !(material.mix_first < m && material.mix_second < m && material.mix_amount >= 0.0f &&
              material.mix_amount <= 1.0f))
            return Invalid(absl::StrCat(name, ": a mix of materials ", material.mix_first, " and ",
                                        material.mix_second, " by ", material.mix_amount));
        if (!(material.alpha >= 0.0f && material.alpha <= 1.0f && material.alpha_cutoff >= 0.0f &&
              material.alpha_cutoff <= 1.0f && material.surface_flags <= gpu::kSurfaceFlags))
            return Invalid(absl::StrCat(name, ": alpha out of range, or unknown surface flags"));
        for (const int32_t texture : material.Textures()) {
            if (texture == kNoTexture) continue;
            if (texture < 0 || static_cast<size_t>(texture) >= scene.textures.size() ||
                (scene.textures[texture]->texels.empty() &&
                 !scene.textures[texture]->IsProcedural()))
                return Invalid(
                    absl::StrCat(name, ": texture ", texture, " of ", scene.textures.size()));
            if (scene.uvs.size() != scene.positions.size())
                return Invalid(absl::StrCat(name, " has a texture, the vertices no coordinates"));
        }
        // Normal maps, cut-outs and emission are read as images.
        for (const int32_t texture :
             {material.normal_texture, material.alpha_texture, material.emission_texture})
            if (texture != kNoTexture && scene.textures[texture]->IsProcedural())
                return Invalid(absl::StrCat(name, ": texture ", texture, " is not an image"));
    }
    return absl::OkStatus();
}

// Whether material `m`, or one a mix of it may be, emits.
bool Emits(const Scene& scene, uint32_t m) {
    const Material& material = scene.materials[m];
    if (material.IsEmissive()) return true;
    // A mix's materials come before it (CheckMaterials), so this ends.
    return material.type == MaterialType::kMix &&
           (Emits(scene, material.mix_first) || Emits(scene, material.mix_second));
}

// Curves: control points and normals finite, widths finite, not negative and not both 0, a
// ribbon's normals unit length, a known type, a material in range that emits nothing (emitters
// are triangles). After CheckMaterials.
absl::Status CheckCurves(const Scene& scene) {
    for (size_t c = 0; c < scene.curves.size(); ++c) {
        const Curve& curve = scene.curves[c];
        const std::string name = absl::StrCat("curve ", c);
        if (static_cast<uint32_t>(curve.type) > static_cast<uint32_t>(CurveType::kRibbon))
            return Invalid(
                absl::StrCat(name, ": unknown type ", static_cast<uint32_t>(curve.type)));
        if (!std::all_of(curve.control.begin(), curve.control.end(),
                         [](const Vec3& p) { return Finite(p); }) ||
            !Finite(curve.normal[0]) || !Finite(curve.normal[1]))
            return Invalid(absl::StrCat(name, ": a point or normal not finite"));
        if (!(Finite(curve.width[0]) && Finite(curve.width[1]) && curve.width[0] >= 0 &&
              curve.width[1] >= 0 && curve.Radius() > 0))
            return Invalid(
                absl::StrCat(name, ": widths ", curve.width[0], " and ", curve.width[1]));
        if (curve.type == CurveType::kRibbon)
            for (const Vec3& n : curve.normal)
                if (!(std::abs(Length(n) - 1.0f) < 1e-3f))
                    return Invalid(absl::StrCat(name, ": a ribbon normal not of unit length"));
        if (curve.material >= scene.materials.size())
            return Invalid(absl::StrCat(name, " uses material ", curve.material, " of ",
                                        scene.materials.size()));
        if (Emits(scene, curve.material))
            return Invalid(absl::StrCat(name, " emits light (only triangles may)"));
    }
    return absl::OkStatus();
}

absl::Status CheckGeometry(const Scene& scene) {
    const size_t vertices = scene.positions.size();
    if (!std::all_of(scene.positions.begin(), scene.positions.end(),
                     [](const Vec3& p) { return Finite(p); }) ||
        !std::all_of(scene.normals.begin(), scene.normals.end(),
                     [](const Vec3& n) { return Finite(n); }) ||
        !std::all_of(scene.uvs.begin(), scene.uvs.end(),
                     [](const Point2& uv) { return Finite(uv); }) ||
        !std::all_of(scene.tangents.begin(), scene.tangents.end(),
                     [](const Vec3& t) { return Finite(t); }))
        return Invalid("a vertex that is not finite");
    if (!scene.uvs.empty() && scene.uvs.size() != vertices)
        return Invalid("texture coordinates not one per vertex");
    if (!scene.tangents.empty() && scene.tangents.size() != vertices)
        return Invalid("tangents not one per vertex");
    if (!scene.colors.empty() && scene.colors.size() != vertices)
        return Invalid("vertex colours not one per vertex");
    // In [0, 1] (NaN fails): a colour multiplies albedos, which must not exceed 1.
    const auto unit = [](float x) { return x >= 0.0f && x <= 1.0f; };
    for (const VertexColor& color : scene.colors)
        if (!unit(color.rgb.x) || !unit(color.rgb.y) || !unit(color.rgb.z) || !unit(color.alpha))
            return Invalid("a vertex colour outside [0, 1]");
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const Triangle& triangle = scene.triangles[t];
        for (uint32_t v : triangle.vertex)
            if (v >= vertices)
                return Invalid(absl::StrCat("triangle ", t, " uses vertex ", v, " of ", vertices));
        if (triangle.material >= scene.materials.size())
            return Invalid(absl::StrCat("triangle ", t, " uses material ", triangle.material,
                                        " of ", scene.materials.size()));
        if (triangle.smooth && scene.normals.size() != vertices)
            return Invalid(
                absl::StrCat("triangle ", t, " is smooth, the vertices have no normals"));
        if (!Finite(triangle.normal))
            return Invalid(absl::StrCat("triangle ", t, ": normal not finite"));
    }
    uint64_t first_prototype_triangle = scene.triangles.size();
    uint64_t first_prototype_curve = scene.curves.size();
    for (size_t p = 0; p < scene.prototypes.size(); ++p) {
        const Prototype& prototype = scene.prototypes[p];
        if (uint64_t(prototype.first_triangle) + prototype.triangle_count > scene.triangles.size())
            return Invalid(absl::StrCat("prototype ", p, ": triangles out of range"));
        if (uint64_t(prototype.first_curve) + prototype.curve_count > scene.curves.size())
            return Invalid(absl::StrCat("prototype ", p, ": curves out of range"));
        first_prototype_triangle =
            std::min<uint64_t>(first_prototype_triangle, prototype.first_triangle);
        first_prototype_curve = std::min<uint64_t>(first_prototype_curve, prototype.first_curve);
    }
    if (!scene.prototypes.empty() &&
        (scene.prototypes.front().first_triangle != first_prototype_triangle ||
         scene.prototypes.front().first_curve != first_prototype_curve))
        return Invalid("prototypes out of order");
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (instance.prototype >= scene.prototypes.size())
            return Invalid(absl::StrCat("instance ", i, " of prototype ", instance.prototype,
                                        " of ", scene.prototypes.size()));
        if (!Finite(instance.to_world) || !Finite(instance.normal_map))
            return Invalid(absl::StrCat("instance ", i, ": transform not finite"));
    }
    return absl::OkStatus();
}

absl::Status CheckLightsAndCamera(const Scene& scene) {
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const PunctualLight& light = scene.lights[l];
        if (static_cast<uint32_t>(light.type) > static_cast<uint32_t>(LightType::kProjection) ||
            !Finite(light.position) || !Finite(light.direction) || !Finite(light.intensity) ||
            !Finite(light.cos_inner) || !Finite(light.cos_outer) || !Finite(light.range) ||
            light.range < 0 || MinComponent(light.intensity) < 0 || !Finite(light.to_light) ||
            !(light.tan_half_fov > 0 && light.tan_half_fov < 1e6f))
            return Invalid(absl::StrCat("light ", l, ": a value out of range"));
        if (light.HasImage() != (light.image != nullptr) ||
            (light.image &&
             (light.image->texels.empty() || light.image->IsProcedural() ||
              !std::all_of(light.image->texels.begin(), light.image->texels.end(),
                           [](const Rgb& t) { return Finite(t) && MinComponent(t) >= 0; }))))
            return Invalid(absl::StrCat("light ", l, ": its image is missing or out of range"));
    }
    const Camera& camera = scene.camera;
    if (!Finite(camera.position) || !Finite(camera.forward) || !Finite(camera.right) ||
        !Finite(camera.up) || !Finite(camera.y_fov) || !Finite(camera.aspect_ratio) ||
        static_cast<uint32_t>(camera.projection) > static_cast<uint32_t>(Projection::kSpherical) ||
        !Finite(camera.window.x_min) || !Finite(camera.window.x_max) ||
        !Finite(camera.window.y_min) || !Finite(camera.window.y_max) ||
        !Finite(camera.lens_radius) || !Finite(camera.focal_distance))
        return Invalid("camera not finite");
    if (const std::optional<std::string> problem = FilterProblem(camera.filter))
        return Invalid(absl::StrCat("the camera's pixel filter: ", *problem));
    if (!Finite(scene.bounds.lower) || !Finite(scene.bounds.upper))
        return Invalid("bounds not finite");
    if (scene.hints.width < 0 || scene.hints.height < 0 ||
        !std::isfinite(scene.hints.initial_radius) || scene.hints.initial_radius < 0)
        return Invalid("render hints out of range");
    if (scene.environment) {
        const Environment& environment = *scene.environment;
        const Texture& image = environment.image;
        const bool uniform = environment.mapping == EnvironmentMapping::kUniform;
        if (static_cast<uint32_t>(environment.mapping) >
                static_cast<uint32_t>(EnvironmentMapping::kLatLong) ||
            !Finite(environment.scale) || MinComponent(environment.scale) < 0 ||
            !Finite(environment.to_map))
            return Invalid("environment: a value out of range");
        if (uniform != image.texels.empty() || image.IsProcedural() || image.width < 0 ||
            image.height < 0 ||
            uint64_t(image.width) * uint64_t(image.height) != image.texels.size() ||
            (environment.mapping == EnvironmentMapping::kEqualArea && image.width != image.height))
            return Invalid(absl::StrCat("environment: a ", image.width, "x", image.height,
                                        " map with ", image.texels.size(), " texels"));
        for (const Rgb& texel : image.texels)
            if (!Finite(texel) || MinComponent(texel) < 0)
                return Invalid("environment: a texel not finite or negative");
        // The map's frame must be a rotation: its rows unit length and orthogonal.
        const auto& m = environment.to_map;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                const float dot =
                    m[3 * a] * m[3 * b] + m[3 * a + 1] * m[3 * b + 1] + m[3 * a + 2] * m[3 * b + 2];
                if (!(std::abs(dot - (a == b ? 1.0f : 0.0f)) < 1e-4f))
                    return Invalid("environment: its frame is not a rotation");
            }
    }
    return absl::OkStatus();
}

}  // namespace

std::string EncodePreparedScene(const Scene& scene) {
    ByteWriter payload;
    WritePayload(scene, payload);
    const std::string digest = Sha256Hex(payload.Bytes());
    ByteWriter out;
    out.Bytes().append(kMagic, sizeof(kMagic));
    out.Value<uint32_t>(kPreparedSceneVersion);
    out.Value<uint64_t>(payload.Bytes().size());
    out.Bytes().append(digest);
    out.Bytes().append(payload.Bytes());
    return std::move(out.Bytes());
}

absl::StatusOr<Scene> DecodePreparedScene(std::string_view bytes, bool texture_filter) {
    if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        return Invalid("not a prepared scene (no header)");
    ByteReader header(bytes.substr(sizeof(kMagic), 12));
    uint32_t version = 0;
    uint64_t size = 0;
    header.Value(&version), header.Value(&size);
    if (version != kPreparedSceneVersion)
        return Invalid(absl::StrCat("version ", version, ", this worker reads version ",
                                    kPreparedSceneVersion));
    const std::string_view digest = bytes.substr(sizeof(kMagic) + 12, kDigestBytes);
    const std::string_view payload = bytes.substr(kHeaderBytes);
    if (payload.size() != size)
        return Invalid(absl::StrCat(payload.size(), " bytes where the header says ", size));
    if (Sha256Hex(payload) != digest) return Invalid("checksum mismatch (corrupted)");
    Scene scene;
    ByteReader in(payload);
    if (absl::Status status = ReadPayload(in, &scene); !status.ok()) return status;
    // Curves after materials: whether one emits follows mixes, checked to end.
    for (const auto& check : {CheckGeometry, CheckMaterials, CheckCurves, CheckLightsAndCamera})
        if (absl::Status status = check(scene); !status.ok()) return status;
    if (texture_filter && !scene.textures.empty())
        scene.texture_filter = MakeTextureFilter(scene.textures);
    return scene;
}

}  // namespace pf
