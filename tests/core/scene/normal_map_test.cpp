// Normal and bump maps: the shared functions against their definitions (a flat texel changes
// nothing, a tilted one tilts toward the tangent or up the image, a displacement ramp tilts as
// its slope says), MikkTSpace-style tangents, glTF's normalTexture and pbrt's normalmap and
// displacement through the loaders to Scene::Surface, and Veach's adjoint factors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"
#include "core/scene/tangents.h"
#include "core/scene_io/scene_loader.h"
#include "core/shared/shading_normal.h"
#include "tests/core/scene_io/pbrt_test_support.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/png_fixture.h"

namespace pf {
namespace {

void ExpectNear(const Vec3& actual, const Vec3& expected, float tolerance, const char* what) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

// A texel's tangent-space normal, as glTF and pbrt define it: 2 c - 1 per channel.
Vec3 Decoded(float r, float g, float b) { return {2 * r - 1, 2 * g - 1, 2 * b - 1}; }

TEST(NormalMapTest, AFlatTexelChangesNothingAndATiltedOneTiltsInTheTangentFrame) {
    const Vec3 n(0, 0, 1), t(1, 0, 0);
    // 0.5 is 0 exactly: the same normal, bit for bit, whatever the tangent and scale.
    EXPECT_EQ(gpu::NormalFromMap(n, t, 1, Rgb(0.5f, 0.5f, 1.0f), 1), n);
    EXPECT_EQ(gpu::NormalFromMap(n, Vec3(0.3f, 0.9f, 0.2f), -1, Rgb(0.5f, 0.5f, 1.0f), 3), n);
    // x follows the tangent (made perpendicular to n first), y the bitangent sign x cross(n, t).
    const Vec3 tilted_x = gpu::NormalFromMap(n, Vec3(2, 0, 1), 1, Rgb(0.75f, 0.5f, 0.9f), 1);
    ExpectNear(tilted_x, Normalize(Vec3(0.5f, 0, 0.8f)), 1e-6f, "x along the tangent");
    const Vec3 up = gpu::NormalFromMap(n, t, 1, Rgb(0.5f, 0.75f, 0.9f), 1);
    ExpectNear(up, Normalize(Vec3(0, 0.5f, 0.8f)), 1e-6f, "y along cross(n, t)");
    const Vec3 mirrored = gpu::NormalFromMap(n, t, -1, Rgb(0.5f, 0.75f, 0.9f), 1);
    ExpectNear(mirrored, Normalize(Vec3(0, -0.5f, 0.8f)), 1e-6f, "y against it, mirrored");
    // glTF's scale multiplies x and y; 0 leaves the normal.
    ExpectNear(gpu::NormalFromMap(n, t, 1, Rgb(0.75f, 0.5f, 0.9f), 2),
               Normalize(Vec3(1.0f, 0, 0.8f)), 1e-6f, "scale 2");
    ExpectNear(gpu::NormalFromMap(n, t, 1, Rgb(0.75f, 0.6f, 0.9f), 0), n, 1e-6f, "scale 0");
    // A tangent along n gives some perpendicular frame, never NaN.
    const Vec3 any = gpu::NormalFromMap(n, n, 1, Rgb(0.75f, 0.5f, 0.9f), 1);
    EXPECT_NEAR(Length(any), 1.0f, 1e-6f);
    EXPECT_NEAR(any.z, 0.8f / std::sqrt(0.89f), 1e-6f);
}

TEST(NormalMapTest, ABumpMapTiltsAsTheDisplacementsSlopeSays) {
    const Vec3 n(0, 0, 1), dpdu(2, 0, 0);  // two world units per unit of u
    EXPECT_EQ(gpu::NormalFromBump(n, dpdu, 0, 0), n) << "no slope, no change";
    // d rising 1 per unit of u: a slope of 1/2 along +x, the normal leaning back against it.
    ExpectNear(gpu::NormalFromBump(n, dpdu, 1, 0), Normalize(Vec3(-0.5f, 0, 1)), 1e-6f, "u");
    // d rising with glTF's v, down the image, which pbrt's frame puts along -cross(n, dpdu).
    ExpectNear(gpu::NormalFromBump(n, dpdu, 0, 1), Normalize(Vec3(0, 0.5f, 1)), 1e-6f, "v");
    // dP/du of a triangle from its texture coordinates; none where they span no area.
    ExpectNear(gpu::TriangleDpDu({2, 0, 0}, {0, 3, 0}, {1, 0}, {0, 1}), {2, 0, 0}, 1e-6f, "dpdu");
    EXPECT_EQ(gpu::TriangleDpDu({2, 0, 0}, {0, 3, 0}, {1, 0}, {2, 0}), Vec3(0.0f));
}

TEST(NormalMapTest, TheBitangentPointsUpTheImageOnEitherSide) {
    // u along +x, glTF's v down the image along -y: up the image is +y = cross(+z, +x).
    const Vec3 e1(1, 0, 0), e2(0, 1, 0);
    EXPECT_EQ(gpu::BitangentSign({0, 0, 1}, e1, e2, {1, 0}, {0, -1}), 1.0f);
    // Mirrored in u: the tangent is -x, up the image still +y = -cross(+z, -x).
    EXPECT_EQ(gpu::BitangentSign({0, 0, 1}, e1, e2, {-1, 0}, {0, -1}), -1.0f);
    // Seen from the other side (the normal flipped), the same image needs the other sign.
    EXPECT_EQ(gpu::BitangentSign({0, 0, -1}, e1, e2, {1, 0}, {0, -1}), -1.0f);
}

TEST(NormalMapTest, GeneratedTangentsFollowUAndArePerpendicularToTheNormals) {
    // A quad in z = 0, u along +x; its vertex normals tilted, as a curved mesh's are.
    const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<Point2> uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    const std::vector<Vec3> flat(4, Vec3(0.0f));
    for (const Vec3& t : GenerateTangents(positions, flat, uvs, indices))
        ExpectNear(t, {1, 0, 0}, 1e-6f, "flat: +x");
    std::vector<Vec3> tilted(4, Normalize(Vec3(0.3f, 0.1f, 1)));
    for (const Vec3& t : GenerateTangents(positions, tilted, uvs, indices)) {
        EXPECT_NEAR(Length(t), 1.0f, 1e-6f);
        EXPECT_NEAR(Dot(t, tilted[0]), 0.0f, 1e-6f);
        EXPECT_GT(t.x, 0.9f);
    }
    // u mirrored: the tangent turns with it.
    const std::vector<Point2> mirrored = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
    for (const Vec3& t : GenerateTangents(positions, flat, mirrored, indices))
        ExpectNear(t, {-1, 0, 0}, 1e-6f, "mirrored: -x");
    // No texture-coordinate area: still a unit tangent perpendicular to the normal.
    const std::vector<Point2> none(4, Point2{0.5f, 0.5f});
    for (const Vec3& t : GenerateTangents(positions, flat, none, indices)) {
        EXPECT_NEAR(Length(t), 1.0f, 1e-6f);
        EXPECT_NEAR(t.z, 0.0f, 1e-6f);
    }
}

// The unit quad of LitQuadScene with u along +x and glTF's v down the image (-y), a normal
// texture of two equal texels `texel` (8-bit) and scale `scale`.
Scene NormalMappedQuad(const std::array<unsigned char, 3>& texel, float scale) {
    testing::TestScene scene = testing::LitQuadScene();
    scene.meshes[0].uvs = {0, 1, 1, 1, 1, 0, 0, 1, 1, 0, 0, 0};
    scene.materials[0].normal_png_base64 = absl::Base64Escape(testing::TwoTexelPng(
        {texel[0], texel[1], texel[2], texel[0], texel[1], texel[2]}, "normal.png"));
    scene.materials[0].normal_scale = scale;
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "normal.gltf"));
    EXPECT_TRUE(loaded.ok()) << loaded.status();
    return loaded.ok() ? *loaded : Scene{};
}

TEST(NormalMapTest, GltfsNormalTextureTiltsTheShadingNormalInItsFrame) {
    const Scene scene = NormalMappedQuad({191, 217, 223}, 0.5f);
    ASSERT_FALSE(scene.triangles.empty());
    const Material& quad = scene.materials[scene.triangles[0].material];
    ASSERT_NE(quad.normal_texture, kNoTexture);
    EXPECT_FLOAT_EQ(quad.normal_scale, 0.5f);
    ASSERT_EQ(scene.tangents.size(), scene.positions.size()) << "made, the mesh having none";
    EXPECT_TRUE(scene.NeedsTangents(scene.triangles[0].material));
    // Linear texels (not sRGB): x = 0.498 and y = 0.702 times the scale, along +x and up the
    // image (+y), z = 0.749 along the quad's normal +z.
    const Vec3 m = Decoded(191 / 255.0f, 217 / 255.0f, 223 / 255.0f);
    const Vec3 expected = Normalize(Vec3(m.x * 0.5f, m.y * 0.5f, m.z));
    for (uint32_t t = 0; t < 2; ++t) {
        const SurfacePoint surface = scene.Surface({1.0f, t, 0.3f, 0.3f});
        ExpectNear(surface.geometric_normal, {0, 0, 1}, 1e-6f, "the quad faces +z");
        ExpectNear(surface.shading_normal, expected, 1e-5f, "tilted toward +x and +y");
    }
    // The light's triangles, without a normal map, keep their normal.
    const SurfacePoint light = scene.Surface({1.0f, 2, 0.3f, 0.3f});
    EXPECT_EQ(light.shading_normal, light.geometric_normal);
}

TEST(NormalMapTest, PbrtsNormalmapAndDisplacementTiltTheShadingNormal) {
    using namespace pbrt_test;
    const std::string normal = TwoTexelPng({191, 128, 223, 191, 128, 223}, "pbrt-normal.png");
    const std::string ramp = TwoTexelPng({0, 0, 0, 255, 255, 255}, "pbrt-ramp.png");
    ASSERT_FALSE(normal.empty() || ramp.empty());
    const std::string world =
        std::string("Texture \"d\" \"float\" \"imagemap\" \"string filename\" \"ramp.png\" ") +
        "\"string wrap\" \"clamp\" \"float scale\" 0.5\n"
        "Material \"diffuse\" \"string normalmap\" \"normal.png\"\n" +
        kQuad + "Material \"diffuse\" \"texture displacement\" \"d\"\n" + kQuad;
    const absl::StatusOr<Scene> scene =
        Load(Bundle(world, {{"normal.png", normal}, {"ramp.png", ramp}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->triangles.size(), 4u);
    // At u = 0.25 (b1 = 0.25 toward a corner of u = 1; the quad runs over x from -1 to 1).
    const SurfacePoint mapped = scene->Surface({1.0f, 0, 0.25f, 0.0f});
    const Vec3 n = mapped.geometric_normal;
    const Vec3 m = Decoded(191 / 255.0f, 128 / 255.0f, 223 / 255.0f);
    // x along dP/du (+x), y up the image (pbrt's +v, here +y), z along the normal.
    const Vec3 t(1, 0, 0);
    ExpectNear(mapped.shading_normal, Normalize(t * m.x + Vec3(0, 1, 0) * m.y + n * m.z), 1e-5f,
               "normalmap");
    // The displacement: 0 at u = 0.25, 0.5 x 1 a texel (0.5 in u) further: a slope of 1 per
    // unit of u, 1/2 per world unit along +x.
    const SurfacePoint bumped = scene->Surface({1.0f, 2, 0.25f, 0.0f});
    ExpectNear(bumped.shading_normal, Normalize(bumped.geometric_normal - t * 0.5f), 1e-5f,
               "displacement");
    EXPECT_TRUE(scene->tangents.size() == scene->positions.size());
    ExpectError(
        Load(Bundle(std::string("Material \"diffuse\" \"string normalmap\" \"no.png\"\n") + kQuad)),
        "no.png");
}

TEST(NormalMapTest, ANegativeDisplacementScaleBumpsInwards) {
    // pbrt-v4 takes a float texture's negative scale (kroken's carpet, scale -3.5): as a
    // displacement, the bump points into the surface, so the ramp of the test above tilts the
    // shading normal the other way (toward +x). Anywhere else a negative texture is refused,
    // naming it.
    using namespace pbrt_test;
    const std::string ramp = TwoTexelPng({0, 0, 0, 255, 255, 255}, "pbrt-ramp.png");
    ASSERT_FALSE(ramp.empty());
    const std::string texture =
        "Texture \"d\" \"float\" \"imagemap\" \"string filename\" \"ramp.png\" "
        "\"string wrap\" \"clamp\" \"float scale\" -0.5\n";
    const absl::StatusOr<Scene> scene =
        Load(Bundle(texture + "Material \"diffuse\" \"texture displacement\" \"d\"\n" + kQuad,
                    {{"ramp.png", ramp}}));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const SurfacePoint bumped = scene->Surface({1.0f, 0, 0.25f, 0.0f});
    ExpectNear(bumped.shading_normal, Normalize(bumped.geometric_normal + Vec3(0.5f, 0, 0)), 1e-5f,
               "displacement of scale -0.5");
    ExpectError(
        Load(Bundle(texture + "Material \"conductor\" \"texture roughness\" \"d\"\n" + kQuad,
                    {{"ramp.png", ramp}})),
        "texture \"d\": its values must be non-negative (its scale is -0.5; only a "
        "displacement's may be below 0)");
    ExpectError(Load(Bundle("Texture \"c\" \"spectrum\" \"imagemap\" \"string filename\" "
                            "\"ramp.png\" \"float scale\" -1\n",
                            {{"ramp.png", ramp}})),
                "Texture \"c\": its values must be finite and non-negative");
}

TEST(NormalMapTest, PhotonsCarryVeachsAdjointFactors) {
    const Vec3 n(0, 0, 1), tilted = Normalize(Vec3(0.4f, 0, 1));
    const Vec3 arriving = Normalize(Vec3(0.3f, 0.2f, -1)), leaving = Normalize(Vec3(-0.5f, 0, 1));
    EXPECT_EQ(gpu::ShadingArrival(arriving, n, n), 1.0f);
    EXPECT_EQ(gpu::ShadingDeparture(leaving, n, n), 1.0f);
    EXPECT_FLOAT_EQ(gpu::ShadingArrival(arriving, tilted, n),
                    std::abs(Dot(arriving, tilted)) / std::abs(Dot(arriving, n)));
    EXPECT_FLOAT_EQ(gpu::ShadingDeparture(leaving, tilted, n),
                    std::abs(Dot(leaving, n)) / std::abs(Dot(leaving, tilted)));
    // Along the surface or the shading plane: zero, not infinity or NaN.
    EXPECT_EQ(gpu::ShadingArrival({1, 0, 0}, tilted, n), 0.0f);
    EXPECT_EQ(gpu::ShadingDeparture({0, 1, 0}, tilted, n), 0.0f);
}

}  // namespace
}  // namespace pf
