// The prepared scene a coordinator sends its workers: lossless and deterministic for every
// shipped scene (glTF and pbrt, instanced and textured ones too), leaving out what no tracing
// reads, and refusing hostile bytes with an error naming what is wrong.
#include "core/scene/prepared_scene.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/scene/texture_program.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/coat.h"
#include "core/util/byte_stream.h"
#include "core/util/sha256.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

std::string Shipped(const std::string& name) {
    return std::string(PF_SOURCE_DIR) + "/scenes/" + name;
}

// Field by field, bit for bit (floats compared by their bytes, so -0 and NaN count).
template <typename T>
bool SameBytes(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}
template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void ExpectSameScene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.source, b.source);
    EXPECT_TRUE(SameBytes(a.positions, b.positions));
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (size_t t = 0; t < a.triangles.size(); ++t) {
        const Triangle &x = a.triangles[t], &y = b.triangles[t];
        ASSERT_TRUE(std::equal(x.vertex, x.vertex + 3, y.vertex) && x.material == y.material &&
                    x.smooth == y.smooth && SameBytes(x.normal, y.normal))
            << "triangle " << t;
        // What Surface() reads of the optional arrays is kept.
        for (uint32_t v : x.vertex) {
            if (x.smooth) {
                EXPECT_TRUE(SameBytes(a.normals[v], b.normals[v]));
            }
            if (a.materials[x.material].base_color_texture != kNoTexture) {
                EXPECT_TRUE(SameBytes(a.uvs[v], b.uvs[v]));
            }
        }
    }
    EXPECT_TRUE(SameBytes(a.prototypes, b.prototypes));
    EXPECT_TRUE(SameBytes(a.instances, b.instances));
    EXPECT_TRUE(SameBytes(a.materials, b.materials));
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t t = 0; t < a.textures.size(); ++t) {
        EXPECT_EQ(a.textures[t]->width, b.textures[t]->width);
        EXPECT_TRUE(SameBytes(a.textures[t]->texels, b.textures[t]->texels));
        EXPECT_TRUE(SameBytes(a.textures[t]->program, b.textures[t]->program));
    }
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t l = 0; l < a.lights.size(); ++l) {
        const PunctualLight &x = a.lights[l], &y = b.lights[l];
        EXPECT_TRUE(x.type == y.type && SameBytes(x.position, y.position) &&
                    SameBytes(x.direction, y.direction) && SameBytes(x.intensity, y.intensity) &&
                    x.cos_inner == y.cos_inner && x.cos_outer == y.cos_outer &&
                    x.smooth_falloff == y.smooth_falloff && x.name == y.name);
    }
    EXPECT_TRUE(SameBytes(a.camera, b.camera));
    EXPECT_TRUE(SameBytes(a.bounds, b.bounds));
    EXPECT_TRUE(SameBytes(a.hints, b.hints));
    ASSERT_EQ(a.environment.has_value(), b.environment.has_value());
    if (a.environment) {
        const Environment &x = *a.environment, &y = *b.environment;
        EXPECT_TRUE(x.mapping == y.mapping && SameBytes(x.scale, y.scale) &&
                    SameBytes(x.to_map, y.to_map) && x.name == y.name &&
                    x.image.width == y.image.width && x.image.height == y.image.height &&
                    SameBytes(x.image.texels, y.image.texels));
        ASSERT_EQ(x.portal.has_value(), y.portal.has_value());
        if (x.portal) {
            EXPECT_TRUE(SameBytes(x.portal->corner, y.portal->corner) &&
                        SameBytes(x.portal->edge_u, y.portal->edge_u) &&
                        SameBytes(x.portal->edge_v, y.portal->edge_v) &&
                        Length(x.portal->normal - y.portal->normal) < 1e-6f);
        }
    }
}

class ShippedScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScenes, RoundTripBitForBitAndEncodeTheSameBytesTwice) {
    const absl::StatusOr<Scene> loaded = LoadScene(Shipped(GetParam()));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    const std::string bytes = EncodePreparedScene(*loaded);
    EXPECT_EQ(EncodePreparedScene(*loaded), bytes);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ExpectSameScene(*loaded, *decoded);
    EXPECT_EQ(EncodePreparedScene(*decoded), bytes);
}

INSTANTIATE_TEST_SUITE_P(All, ShippedScenes,
                         ::testing::Values("cornell-box.gltf", "cornell-glass.gltf",
                                           "cornell-glossy.gltf", "caustic-glass.gltf",
                                           "furnace.gltf", "pbrt/cornell-room.pbrt",
                                           "pbrt/caustic-glass.pbrt", "cornell-bumpy.gltf",
                                           "cornell-velvet.gltf"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// A textured, instanced glTF: texels and instances survive, the texture filter is rebuilt.
Scene TexturedInstancedScene() {
    testing::TestScene scene = testing::LitQuadScene();
    scene.materials[0].texture_png_base64 =
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGP4z8DQ0NAAAAkBAoCZxGkyAAAAAElFTk"
        "SuQmCC";
    scene.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    scene.extra_nodes = {R"({"mesh":0,"translation":[3,0,0]})",
                         R"({"mesh":0,"translation":[-3,0,0]})"};
    absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "prepared-textured.gltf"));
    EXPECT_TRUE(loaded.ok()) << loaded.status();
    return loaded.ok() ? std::move(*loaded) : Scene();
}

TEST(PreparedSceneTest, TexturesAndInstancesSurviveAndTheFilterIsRebuilt) {
    const Scene loaded = TexturedInstancedScene();
    ASSERT_FALSE(loaded.textures.empty());
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(EncodePreparedScene(loaded), true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ExpectSameScene(loaded, *decoded);
    ASSERT_NE(decoded->texture_filter, nullptr);
    for (float footprint : {0.0f, 0.3f, 2.0f}) {
        const Rgb a = loaded.texture_filter->Sample(0, 0.3f, 0.6f, footprint);
        const Rgb b = decoded->texture_filter->Sample(0, 0.3f, 0.6f, footprint);
        EXPECT_TRUE(SameBytes(a, b)) << footprint;
    }
    const absl::StatusOr<Scene> photons_only =
        DecodePreparedScene(EncodePreparedScene(loaded), false);
    ASSERT_TRUE(photons_only.ok());
    EXPECT_EQ(photons_only->texture_filter, nullptr);
}

// Every texture a material reads, not only colour and emission, reaches the worker: cut-outs',
// roughness's and a mix's amount's.
TEST(PreparedSceneTest, EveryTextureAMaterialReadsSurvives) {
    Scene scene = TexturedInstancedScene();
    ASSERT_EQ(scene.textures.size(), 1u);
    for (const float scale : {0.5f, 0.25f, 0.125f}) {
        Texture texture = *scene.textures[0];
        for (Rgb& texel : texture.texels) texel = texel * scale;
        scene.textures.push_back(std::make_shared<const Texture>(std::move(texture)));
    }
    Material& floor = scene.materials[scene.triangles[0].material];
    floor.base_color_texture = kNoTexture;
    floor.alpha_texture = 1;
    floor.type = MaterialType::kRoughConductor;
    floor.roughness = 0.5f;
    floor.roughness_texture = 2;
    Material mix;
    mix.type = MaterialType::kMix;
    mix.mix_first = scene.triangles[0].material;
    mix.mix_second = scene.triangles.back().material;
    mix.mix_texture = 3;
    scene.materials.push_back(mix);
    scene.triangles[1].material = static_cast<uint32_t>(scene.materials.size() - 1);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(EncodePreparedScene(scene), true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ExpectSameScene(scene, *decoded);
    for (size_t t = 1; t < 4; ++t) EXPECT_FALSE(decoded->textures[t]->texels.empty()) << t;
}

// A procedural texture's program survives, and the image it reads though no material names it;
// a broken program is refused.
TEST(PreparedSceneTest, ProceduralTexturesAndTheirImagesSurvive) {
    Scene scene = TexturedInstancedScene();
    ASSERT_EQ(scene.textures.size(), 1u);
    auto mixed = std::make_shared<Texture>();
    TextureProgramWriter write(&mixed->program);
    const double identity[6] = {1, 0, 0, 0, 1, 0};
    write.Image(0, identity);
    write.Solid(gpu::kTextureWrinkled, Transform{}, 0.5f, 8);
    write.Combine(gpu::kTextureMultiply);
    scene.textures.push_back(mixed);
    for (Material& material : scene.materials)
        if (material.base_color_texture == 0) material.base_color_texture = 1;
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(EncodePreparedScene(scene), true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ExpectSameScene(scene, *decoded);
    EXPECT_FALSE(decoded->textures[0]->texels.empty()) << "the program's image is kept";
    const std::string refused = [&] {
        mixed->program.pop_back();  // an operand left over
        const absl::StatusOr<Scene> broken = DecodePreparedScene(EncodePreparedScene(scene), true);
        return broken.ok() ? std::string() : std::string(broken.status().message());
    }();
    EXPECT_NE(refused.find("texture 1: texture program leaves 2 values"), std::string::npos)
        << refused;
    // Cut-outs, bump and normal maps and emission read images.
    scene.textures.back() = std::make_shared<const Texture>(*decoded->textures[1]);
    scene.materials[0].alpha_texture = 1;
    const absl::StatusOr<Scene> cut = DecodePreparedScene(EncodePreparedScene(scene), true);
    ASSERT_FALSE(cut.ok());
    EXPECT_NE(cut.status().message().find("material 0: texture 1 is not an image"),
              std::string::npos)
        << cut.status();
}

TEST(PreparedSceneTest, CoatsSurvive) {
    Scene scene = *LoadScene(Shipped("cornell-box.gltf"));
    scene.materials[0].coat_ior = 1.5f;
    scene.materials[0].coat_roughness = 0.2f;
    scene.materials[0].coat_thickness = 0.01f;
    scene.materials[0].coat_depth = 7;
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(EncodePreparedScene(scene), true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ExpectSameScene(scene, *decoded);
    EXPECT_EQ(decoded->materials[0].coat_depth, 7u);
}

// An environment map (a latitude-longitude image of floats) and a uniform one, with and
// without a portal, survive.
TEST(PreparedSceneTest, EnvironmentsSurvive) {
    Scene scene = TexturedInstancedScene();
    Environment& environment = scene.environment.emplace();
    environment.mapping = EnvironmentMapping::kLatLong;
    environment.image.width = 8, environment.image.height = 4;
    for (int i = 0; i < 32; ++i) environment.image.texels.push_back(Rgb(0.1f * i, 3.5f, 1e-3f * i));
    environment.scale = Rgb(2.0f, 1.0f, 0.5f);
    environment.to_map = RotationAboutUp(33);
    environment.name = "sky.exr";
    for (int uniform = 0; uniform < 3; ++uniform) {
        if (uniform == 1) environment = Environment{};
        if (uniform == 2)  // with a portal
            environment.portal = *EnvironmentPortal::FromCorners(
                {Vec3(1, 0.5f, -2), Vec3(1, 0.5f, 2), Vec3(1, 2.5f, 2), Vec3(1, 2.5f, -2)});
        const std::string bytes = EncodePreparedScene(scene);
        const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, false);
        ASSERT_TRUE(decoded.ok()) << decoded.status();
        ExpectSameScene(scene, *decoded);
        EXPECT_EQ(EncodePreparedScene(*decoded), bytes);
    }
}

TEST(PreparedSceneTest, ImageLightsSurvive) {
    // A goniometric and a projection light: their images, frames and frustum come back, and
    // the bytes re-encode the same.
    Scene scene = TexturedInstancedScene();
    for (const LightType type : {LightType::kGoniometric, LightType::kProjection}) {
        PunctualLight light;
        light.type = type;
        light.position = Vec3(1, 2, 3);
        light.intensity = Rgb(4.0f, 5.0f, 6.0f);
        light.image = std::make_shared<const Texture>(
            Texture{2, 2, {Rgb(1.0f), Rgb(2.0f), Rgb(0.5f), Rgb(0.0f, 1.0f, 2.0f)}});
        light.to_light = RotationAboutUp(20);
        light.tan_half_fov = 0.7f;
        scene.lights.push_back(light);
    }
    const std::string bytes = EncodePreparedScene(scene);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, false);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ASSERT_EQ(decoded->lights.size(), scene.lights.size());
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const PunctualLight &a = scene.lights[l], &b = decoded->lights[l];
        EXPECT_EQ(a.type, b.type);
        EXPECT_EQ(a.to_light, b.to_light);
        EXPECT_EQ(a.tan_half_fov, b.tan_half_fov);
        ASSERT_EQ(a.image == nullptr, b.image == nullptr);
        if (a.image) {
            EXPECT_EQ(a.image->texels, b.image->texels);
        }
    }
    EXPECT_EQ(EncodePreparedScene(*decoded), bytes);
}

TEST(PreparedSceneTest, VertexColoursAndSurfaceFlagsTravel) {
    // The floor's colours (its alpha read under BLEND) and its single-sided surface.
    testing::TestScene built = testing::LitQuadScene();
    built.materials[0].extra = R"(,"alphaMode":"BLEND")";
    for (int v = 0; v < 6; ++v)
        built.meshes[0].colors.insert(built.meshes[0].colors.end(), {0.1f * v, 0.5f, 1, 0.75f});
    const Scene scene = *LoadScene(testing::WriteGltf(built, "colors-travel.gltf"));
    const uint32_t floor = scene.triangles[0].material;
    ASSERT_EQ(scene.materials[floor].surface_flags,
              gpu::kSurfaceSingleSided | gpu::kSurfaceVertexAlpha);
    const std::string bytes = EncodePreparedScene(scene);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, false);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ASSERT_EQ(decoded->colors.size(), scene.colors.size());
    for (size_t v = 0; v < scene.colors.size(); ++v) {
        EXPECT_EQ(decoded->colors[v].rgb, scene.colors[v].rgb);
        EXPECT_EQ(decoded->colors[v].alpha, scene.colors[v].alpha);
    }
    EXPECT_EQ(decoded->materials[floor].surface_flags, scene.materials[floor].surface_flags);
    EXPECT_EQ(EncodePreparedScene(*decoded), bytes);
    // A scene without colours carries none.
    EXPECT_TRUE(
        DecodePreparedScene(EncodePreparedScene(*LoadScene(Shipped("cornell-box.gltf"))), false)
            ->colors.empty());
}

TEST(PreparedSceneTest, WhatNoTracingReadsIsLeftOut) {
    // cornell-box has no smooth triangle and no texture: no normals, no texture coordinates.
    Scene scene = *LoadScene(Shipped("cornell-box.gltf"));
    scene.normals.assign(scene.positions.size(), Vec3(0, 0, 1));
    scene.uvs.assign(scene.positions.size(), Point2(0.5f, 0.5f));
    auto unread = std::make_shared<Texture>();
    unread->width = unread->height = 64;
    unread->texels.assign(64 * 64, Rgb(0.5f));
    scene.textures.push_back(unread);
    const std::string bytes = EncodePreparedScene(scene);
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, true);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_TRUE(decoded->normals.empty());
    EXPECT_TRUE(decoded->uvs.empty());
    ASSERT_EQ(decoded->textures.size(), 1u);  // indices hold; its texels stay behind
    EXPECT_TRUE(decoded->textures[0]->texels.empty());
    EXPECT_LT(bytes.size(),
              EncodePreparedScene(*LoadScene(Shipped("cornell-box.gltf"))).size() + 1024);
}

// The header EncodePreparedScene writes (magic, version, size, SHA-256) around `payload`, so
// that tests and the fuzzer reach the checks behind the checksum.
std::string Framed(const std::string& payload, uint32_t version = kPreparedSceneVersion) {
    ByteWriter out;
    out.Bytes().append("PFSCENE", 8);
    out.Value<uint32_t>(version);
    out.Value<uint64_t>(payload.size());
    out.Bytes().append(Sha256Hex(payload));
    out.Bytes().append(payload);
    return std::move(out.Bytes());
}

void ExpectRefused(const std::string& bytes, const std::string& naming) {
    const absl::StatusOr<Scene> decoded = DecodePreparedScene(bytes, true);
    ASSERT_FALSE(decoded.ok()) << "accepted; expected an error naming '" << naming << "'";
    EXPECT_TRUE(absl::IsInvalidArgument(decoded.status())) << decoded.status();
    EXPECT_NE(decoded.status().message().find(naming), std::string::npos) << decoded.status();
}

TEST(PreparedSceneTest, HostileBytesAreRefusedNamingWhatIsWrong) {
    const Scene scene = *LoadScene(Shipped("cornell-box.gltf"));
    const std::string bytes = EncodePreparedScene(scene);
    const std::string payload = bytes.substr(8 + 4 + 8 + 64);
    EXPECT_EQ(Framed(payload), bytes);
    ExpectRefused("", "no header");
    ExpectRefused(bytes.substr(0, 50), "no header");
    ExpectRefused(Framed(payload, 99), "version 99");
    for (size_t cut : {size_t{1}, payload.size() / 3, payload.size() - 1})
        ExpectRefused(bytes.substr(0, bytes.size() - cut), "bytes where the header says");
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x40;
    ExpectRefused(flipped, "checksum");
    // Past the checksum (as a hostile coordinator could sign anything): every truncation of
    // the payload is refused, never read past its end.
    for (size_t cut = 0; cut < payload.size(); cut += 1 + payload.size() / 97)
        ExpectRefused(Framed(payload.substr(0, cut)), "prepared scene");
    ExpectRefused(Framed(payload + "x"), "bytes after the end");
    // Broken references, each signed properly.
    const auto broken = [&](auto edit, const std::string& naming) {
        Scene copy = scene;
        edit(copy);
        ExpectRefused(EncodePreparedScene(copy), naming);
    };
    broken([](Scene& s) { s.triangles[3].vertex[1] = 1u << 30; }, "triangle 3 uses vertex");
    broken([](Scene& s) { s.triangles[0].material = 77; }, "triangle 0 uses material 77");
    broken([](Scene& s) { s.positions[2].y = std::nanf(""); }, "not finite");
    broken([](Scene& s) { s.materials[1].base_color_texture = 5; }, "material 1: texture 5");
    broken([](Scene& s) { s.materials[0].type = static_cast<MaterialType>(40); },
           "unknown type 40");
    broken([](Scene& s) { s.materials[0].emission = Rgb(-1.0f); }, "material 0");
    broken([](Scene& s) { s.materials[0].coat_ior = 0.5f; }, "material 0: a coat out of range");
    broken(
        [](Scene& s) {
            s.materials[1].type = MaterialType::kMix;
            s.materials[1].mix_first = 0, s.materials[1].mix_second = 1;  // itself: endless
        },
        "material 1: a mix of materials 0 and 1");
    broken([](Scene& s) { s.materials[0].alpha = 2; }, "material 0: alpha out of range");
    broken([](Scene& s) { s.materials[0].surface_flags = 8; }, "unknown surface flags");
    broken([](Scene& s) { s.colors.assign(3, VertexColor{}); },
           "vertex colours not one per vertex");
    broken(
        [](Scene& s) {
            s.colors.assign(s.positions.size(), VertexColor{Rgb(2.0f), 1.0f});
        },
        "a vertex colour outside [0, 1]");
    broken(
        [](Scene& s) {
            s.materials[1].coat_ior = 1.5f;
            s.materials[1].coat_thickness = std::nanf("");
        },
        "material 1: a coat out of range");
    broken(
        [](Scene& s) {
            s.materials[0].type = MaterialType::kDielectric;
            s.materials[0].coat_ior = 1.5f;
        },
        "material 0: a coat out of range");
    broken([](Scene& s) { s.materials[0].transmittance = Rgb(-0.5f); },
           "material 0: transmittance out of range");
    broken([](Scene& s) { s.materials[0].sheen_color = Rgb(0.5f); },
           "material 0: a sheen out of range");  // on no coat
    broken(
        [](Scene& s) {
            s.materials[0].coat_kind = gpu::kCoatNone;
            s.materials[0].coat_ior = 1.0f;
            s.materials[0].sheen_color = Rgb(1.5f, 0.5f, 0.5f);
        },
        "material 0: a sheen out of range");
    broken(
        [](Scene& s) {
            s.materials[0].coat_kind = gpu::kCoatNone;
            s.materials[0].coat_ior = 1.5f;  // no coat has index 1
        },
        "material 0: a coat out of range");
    broken(
        [](Scene& s) {
            s.materials[0].type = MaterialType::kDielectric;
            s.materials[0].transmittance = Rgb(0.5f);
        },
        "material 0: transmittance out of range");
    broken([](Scene& s) { s.camera.y_fov = std::numeric_limits<float>::infinity(); },
           "camera not finite");
    broken([](Scene& s) { s.prototypes.push_back({0, 1000000, {}}); }, "prototype 0");
    broken([](Scene& s) { s.instances.push_back(Instance{}); }, "instance 0 of prototype 0 of 0");
    broken(
        [](Scene& s) {
            s.triangles[0].smooth = true;
            s.normals.clear();
        },
        "is smooth");
    const auto map = [](Scene& s) {
        Environment& e = s.environment.emplace();
        e.mapping = EnvironmentMapping::kEqualArea;
        e.image.width = e.image.height = 2;
        e.image.texels.assign(4, Rgb(1.0f));
        return &e;
    };
    broken([&](Scene& s) { map(s)->image.texels[2].y = -1; }, "environment: a texel");
    broken([&](Scene& s) { map(s)->image.texels[1].x = std::nanf(""); }, "environment: a texel");
    broken([&](Scene& s) { map(s)->image.width = 4; }, "environment: a 4x2 map with 4 texels");
    broken([&](Scene& s) { map(s)->mapping = static_cast<EnvironmentMapping>(9); },
           "environment: a value out of range");
    broken([&](Scene& s) { map(s)->to_map[0] = 2; }, "environment: its frame is not a rotation");
    broken([&](Scene& s) { map(s)->mapping = EnvironmentMapping::kUniform; },
           "environment: a 2x2 map");
    broken(
        [&](Scene& s) {
            map(s)->portal = {Vec3(0.0f), Vec3(1, 0, 0), Vec3(1, 1, 0), {}};
        },
        "environment: its portal: its corners are not a rectangle");
}

}  // namespace
}  // namespace pf
