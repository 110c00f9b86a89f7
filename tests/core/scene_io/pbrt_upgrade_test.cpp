// pbrt-v3 files read as pbrt-v4's --upgrade rewrites them: each pbrt-v3 form loads to the
// same scene as the pbrt-v4 form --upgrade writes for it, with one note that the file was
// upgraded; pbrt-v3's latitude-longitude environment maps look where pbrt-v3 looked; what
// --upgrade refuses is refused naming its place.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/scene_io/scene_loader.h"
#include "tests/core/scene_io/pbrt_test_support.h"

namespace pf {
namespace {

using namespace pbrt_test;

// Materials, emission, texture coordinates and lights of two scenes agree.
void ExpectSameScene(const Scene& a, const Scene& b, const std::string& what) {
    ASSERT_EQ(a.triangles.size(), b.triangles.size()) << what;
    for (size_t t = 0; t < a.triangles.size(); ++t) {
        const Material& ma = a.materials[a.triangles[t].material];
        const Material& mb = b.materials[b.triangles[t].material];
        EXPECT_EQ(ma.type, mb.type) << what;
        EXPECT_EQ(ma.base_color, mb.base_color) << what;
        EXPECT_EQ(ma.emission, mb.emission) << what;
        EXPECT_EQ(ma.ior, mb.ior) << what;
        EXPECT_EQ(ma.roughness, mb.roughness) << what;
        EXPECT_EQ(ma.base_color_texture == kNoTexture, mb.base_color_texture == kNoTexture) << what;
    }
    ASSERT_EQ(a.uvs.size(), b.uvs.size()) << what;
    for (size_t v = 0; v < a.uvs.size(); ++v)
        EXPECT_TRUE(a.uvs[v].x == b.uvs[v].x && a.uvs[v].y == b.uvs[v].y) << what;
    ASSERT_EQ(a.lights.size(), b.lights.size()) << what;
    for (size_t l = 0; l < a.lights.size(); ++l)
        EXPECT_EQ(a.lights[l].intensity, b.lights[l].intensity) << what;
}

TEST(PbrtUpgradeTest, PbrtV3FormsLoadAsTheFormsUpgradeWrites) {
    // Each pair: what pbrt-v3 wrote, and what pbrt-v4's --upgrade writes for it.
    const std::vector<std::pair<std::string, std::string>> pairs = {
        {"Material \"matte\" \"color Kd\" [0.2 0.4 0.6] \"float sigma\" 0\n",
         "Material \"diffuse\" \"rgb reflectance\" [0.2 0.4 0.6]\n"},
        {"Material \"plastic\" \"color Kd\" [0.5 0.5 0.5] \"color Ks\" [0 0 0] "
         "\"float roughness\" 0.1\n",
         "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"},
        {"Material \"plastic\" \"color Kd\" [0.5 0.2 0.5] \"color Ks\" [0.3 0.3 0.3]\n",
         "Material \"coateddiffuse\" \"rgb reflectance\" [0.5 0.2 0.5]\n"},
        {"Material \"uber\" \"color Kd\" [0.3 0.3 0.3] \"color Ks\" [0 0 0] \"float index\" 1.3 "
         "\"color opacity\" [1 1 1]\n",
         "Material \"diffuse\" \"rgb reflectance\" [0.3 0.3 0.3]\n"},
        {"Material \"substrate\" \"color Kd\" [0.1 0.2 0.3] \"color Ks\" [1 1 1]\n",
         "Material \"coateddiffuse\" \"rgb reflectance\" [0.1 0.2 0.3]\n"},
        {"Material \"glass\" \"float index\" 1.33 \"color Kr\" [1 1 1] \"color Kt\" [1 1 1]\n",
         "Material \"dielectric\" \"float eta\" 1.33\n"},
        {"Material \"metal\" \"float roughness\" 0.2 \"color Kr\" [1 1 1]\n",
         "Material \"conductor\" \"float roughness\" 0.2\n"},
        {"Material \"mirror\"\n",
         "Material \"conductor\" \"float roughness\" 0 \"spectrum eta\" \"metal-Ag-eta\" "
         "\"spectrum k\" \"metal-Ag-k\"\n"},
        {"MakeNamedMaterial \"m\" \"string type\" \"matte\" \"color Kd\" [0.7 0.1 0.1]\n"
         "NamedMaterial \"m\"\n",
         "MakeNamedMaterial \"m\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.7 0.1 0.1]\n"
         "NamedMaterial \"m\"\n"},
        {"AttributeBegin\nAreaLightSource \"area\" \"color L\" [2 3 4] \"integer nsamples\" 8\n" +
             std::string(kQuad) + "AttributeEnd\n",
         "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 3 4]\n" + std::string(kQuad) +
             "AttributeEnd\n"},
        {"AttributeBegin\nAreaLightSource \"area\" \"blackbody L\" [3000 2]\n" +
             std::string(kQuad) + "AttributeEnd\n",
         "AttributeBegin\nAreaLightSource \"diffuse\" \"blackbody L\" [3000] \"float scale\" 2\n" +
             std::string(kQuad) + "AttributeEnd\n"},
        {"LightSource \"point\" \"color I\" [1 2 3] \"color scale\" [2 2 2] \"integer samples\" "
         "4\n",
         "LightSource \"point\" \"rgb I\" [1 2 3] \"float scale\" 2\n"},
        {"Texture \"t\" \"color\" \"constant\" \"color value\" [0.25 0.5 0.75]\n"
         "Material \"matte\" \"texture Kd\" \"t\"\n",
         "Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [0.25 0.5 0.75]\n"
         "Material \"diffuse\" \"texture reflectance\" \"t\"\n"},
        {"Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2] "
         "\"float uv\" [0 0 1 0 0 1]\n",
         "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2] "
         "\"point2 uv\" [0 0 1 0 0 1]\n"},
    };
    for (const auto& [v3, v4] : pairs) {
        std::vector<std::string> warnings;
        const absl::StatusOr<Scene> old_form = Load(Bundle(v3 + kQuad), &warnings);
        ASSERT_TRUE(old_form.ok()) << v3 << old_form.status();
        const absl::StatusOr<Scene> new_form = Load(Bundle(v4 + kQuad));
        ASSERT_TRUE(new_form.ok()) << v4 << new_form.status();
        ExpectSameScene(*old_form, *new_form, v3);
        int notes = 0;
        for (const std::string& line : warnings)
            notes += line.find("read as a pbrt-v3 file") != std::string::npos;
        EXPECT_EQ(notes, 1) << v3;
    }
    // A pbrt-v4 file is not taken for a pbrt-v3 one.
    std::vector<std::string> warnings;
    ASSERT_TRUE(Load(Bundle(pairs[0].second + kQuad), &warnings).ok());
    EXPECT_FALSE(Contains(warnings, "pbrt-v3"));
}

TEST(PbrtUpgradeTest, DroppedParametersAreWarnedOfAsUpgradeWarns) {
    std::vector<std::string> warnings;
    ASSERT_TRUE(Load(Bundle("Material \"plastic\" \"color Ks\" [0.3 0.3 0.3]\n"
                            "Material \"matte\" \"float sigma\" 20\n" +
                            std::string(kQuad)),
                     &warnings)
                    .ok());
    EXPECT_TRUE(Contains(warnings,
                         "scenes/scene.pbrt:6:1: warning: Material \"plastic\": "
                         "\"rgb Ks\" is dropped"));
    EXPECT_TRUE(Contains(warnings,
                         "Material \"matte\": \"sigma\" (Oren-Nayar roughness) is "
                         "dropped"));
}

TEST(PbrtUpgradeTest, ALatLongMapnameLooksWherePbrtV3Looked) {
    // pbrt-v3's map: u = phi / 2 pi and v = theta / pi about the light's +z, phi from +x
    // toward +y. An 8 x 4 map whose texel (x, y) holds (x, y, 1): the direction at polar angle
    // theta and azimuth phi must find texel (phi / (pi / 4), theta / (pi / 4)), rounded down.
    Image image(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) image.pixels[size_t(y) * 8 + x] = Rgb(float(x), float(y), 1.0f);
    const std::string path = testing::TempPath("latlong-v3.exr");
    ASSERT_TRUE(WriteExr(path, image).ok());
    const absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    ASSERT_TRUE(bytes.ok());
    for (const bool turned : {false, true}) {
        // Turned: Rotate 90 about x takes the light's +z to the world's -y.
        const absl::StatusOr<Scene> scene = Load(Bundle(
            std::string(turned ? "AttributeBegin\nRotate 90 1 0 0\n" : "AttributeBegin\n") +
                "LightSource \"infinite\" \"string mapname\" \"sky.exr\" \"color scale\" [2 2 2]\n"
                "AttributeEnd\n" +
                kQuad,
            {{"sky.exr", *bytes}}));
        ASSERT_TRUE(scene.ok()) << scene.status();
        ASSERT_TRUE(scene->environment.has_value());
        for (const double theta : {0.3, 1.0, 1.9, 2.8})
            for (const double phi : {0.2, 1.7, 3.5, 5.9}) {
                const Vec3d light(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                  std::cos(theta));
                const Vec3d world = turned ? Vec3d(light.x, -light.z, light.y) : light;
                const Rgb radiance = scene->environment->Radiance(Vec3(world));
                EXPECT_EQ(radiance.x, 2 * std::floor(phi / (kPiD / 4))) << theta << " " << phi;
                EXPECT_EQ(radiance.y, 2 * std::floor(theta / (kPiD / 4))) << theta << " " << phi;
            }
    }
}

TEST(PbrtUpgradeTest, WhatUpgradeRefusesIsRefusedNamingItsPlace) {
    ExpectError(
        Load(Bundle("LightSource \"point\" \"color scale\" [1 2 3]\n" + std::string(kQuad))),
        "scenes/scene.pbrt:6:1: LightSource: in pbrt-v4, \"scale\" of a light is one "
        "float");
    ExpectError(
        Load(Bundle("Material \"uber\" \"color opacity\" [0.5 0.5 0.5]\n" + std::string(kQuad))),
        "scenes/scene.pbrt:6:1: Material: a non-opaque \"opacity\"");
    ExpectError(
        Load(Bundle("Material \"mix\" \"string namedmaterial1\" \"a\"\n" + std::string(kQuad))),
        "scenes/scene.pbrt:6:1: Material: pbrt-v3's \"mix\" needs");
}

}  // namespace
}  // namespace pf
