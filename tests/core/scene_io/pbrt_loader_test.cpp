// The pbrt-v4 importer: each directive's effect on the scene against what pbrt-v4 defines,
// warnings and errors that point at file:line:column, and bundles that cannot reach outside.
#include "core/scene_io/pbrt/pbrt_loader.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/camera/camera_pass.h"
#include "core/film/exr_io.h"
#include "core/job/job_spec.h"
#include "core/scene_io/pbrt/pbrt_lexer.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"
#include "core/scene_io/scene_files.h"
#include "core/scene_io/scene_loader.h"
#include "tests/core/scene_io/pbrt_test_support.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

using namespace pbrt_test;

double TotalArea(const Scene& scene) {
    double area = 0;
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) area += scene.TriangleArea(t);
    return area;
}

TEST(PbrtLexerTest, TokensKnowWhereTheyStart) {
    const absl::StatusOr<std::vector<pbrt::Token>> tokens =
        pbrt::Tokenize("a.pbrt", "# comment\n  Shape \"sphere\" [ 1.5e-3 ]\n\"esc\\\"aped\"");
    ASSERT_TRUE(tokens.ok()) << tokens.status();
    ASSERT_EQ(tokens->size(), 6u);
    EXPECT_EQ((*tokens)[0].text, "Shape");
    EXPECT_EQ((*tokens)[0].where.ToString(), "a.pbrt:2:3");
    EXPECT_EQ((*tokens)[1].kind, pbrt::TokenKind::kString);
    EXPECT_EQ((*tokens)[1].where.ToString(), "a.pbrt:2:9");
    EXPECT_EQ((*tokens)[3].text, "1.5e-3");
    EXPECT_EQ((*tokens)[5].text, "esc\"aped");
    const absl::StatusOr<std::vector<pbrt::Token>> open =
        pbrt::Tokenize("b.pbrt", "Shape\n  \"sphere");
    ASSERT_FALSE(open.ok());
    EXPECT_NE(open.status().message().find("b.pbrt:2:3"), std::string::npos) << open.status();
}

TEST(PbrtLoaderTest, CameraFollowsLookAtAndFovSpansTheShorterSide) {
    const absl::StatusOr<Scene> scene = Load(Bundle(kQuad));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const Camera& camera = scene->camera;
    EXPECT_NEAR(camera.position.z, -5.0f, 1e-5f);
    EXPECT_NEAR(camera.forward.z, 1.0f, 1e-6f);
    // pbrt's image x is camera +x = cross(up, view direction): world +x here.
    EXPECT_NEAR(camera.right.x, 1.0f, 1e-6f);
    EXPECT_NEAR(camera.up.y, 1.0f, 1e-6f);
    EXPECT_NEAR(camera.aspect_ratio, 2.0f, 1e-6f);
    EXPECT_NEAR(camera.y_fov, 40 * kPi / 180, 1e-6);  // 200x100: y is the shorter side
    EXPECT_EQ(scene->hints.width, 200);
    EXPECT_EQ(scene->hints.height, 100);

    SceneBundle tall = Bundle(kQuad);
    const std::string film = "\"integer xresolution\" 200 \"integer yresolution\" 100";
    std::string& main = tall.files["scene.pbrt"];
    main.replace(main.find(film), film.size(),
                 "\"integer xresolution\" 100 \"integer yresolution\" 200");
    const absl::StatusOr<Scene> portrait = Load(tall);
    ASSERT_TRUE(portrait.ok()) << portrait.status();
    // 100x200: x is the shorter side, so the vertical angle is wider.
    EXPECT_NEAR(portrait->camera.y_fov, 2 * std::atan(2 * std::tan(20 * kPiD / 180)), 1e-6);
}

TEST(PbrtLoaderTest, FilmAndSppmSettingsBecomeTheRenderDefaults) {
    SceneBundle bundle = Bundle(kQuad);
    bundle.files["scene.pbrt"] =
        "Integrator \"sppm\" \"float radius\" 0.25 \"integer iterations\" 10 "
        "\"integer photonsperiteration\" 1000\n" +
        bundle.files["scene.pbrt"];
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(bundle, &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->hints.initial_radius, 0.25);
    const SceneRenderSettings& settings = scene->render_settings;
    EXPECT_EQ(settings.integrator, "sppm");
    EXPECT_EQ(settings.iterations, 10u);
    EXPECT_EQ(settings.photons_per_iteration, 1000u);
    EXPECT_EQ(settings.max_depth, 5);  // pbrt-v4's default
    EXPECT_EQ(settings.integrator_source, "scenes/scene.pbrt:1:1: Integrator \"sppm\"");
    const absl::StatusOr<CameraPassSettings> film =
        FilmFor(JobSpec{}, *scene);  // no --width, --height
    ASSERT_TRUE(film.ok());
    EXPECT_EQ(film->width, 200);
    EXPECT_EQ(film->height, 100);
    JobSpec asked;
    asked.width = 64;
    EXPECT_EQ(FilmFor(asked, *scene)->height, 32);  // the scene's aspect for the side not given
}

TEST(PbrtLoaderTest, TransformsComposeAsPbrtDefines) {
    // Translate then Rotate then Scale: a point p lands at T(R(S(p))).
    const absl::StatusOr<Scene> scene = Load(Bundle(
        "Translate 1 2 3\nRotate 90 0 0 1\nScale 2 2 2\n"
        "Shape \"trianglemesh\" \"point3 P\" [1 0 0  0 1 0  0 0 1] \"integer indices\" [0 1 2]\n"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->positions.size(), 3u);
    // (1,0,0) scaled to (2,0,0), turned 90 degrees about z to (0,2,0), moved to (1,4,3).
    EXPECT_NEAR(scene->positions[0].x, 1.0f, 1e-5f);
    EXPECT_NEAR(scene->positions[0].y, 4.0f, 1e-5f);
    EXPECT_NEAR(scene->positions[0].z, 3.0f, 1e-5f);
}

TEST(PbrtLoaderTest, AttributesRestoreTheStateAndInstancesRepeatAnObject) {
    const std::string world = std::string("AttributeBegin\nTranslate 10 0 0\nAttributeEnd\n") +
                              "ObjectBegin \"quad\"\n" + kQuad +
                              "ObjectEnd\n"
                              "ObjectInstance \"quad\"\nAttributeBegin\nTranslate 0 0 "
                              "5\nObjectInstance \"quad\"\nAttributeEnd\n";
    const absl::StatusOr<Scene> scene = Load(Bundle(world));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->triangles.size(), 2u);  // the object's two triangles, stored once,
    ASSERT_EQ(scene->prototypes.size(), 1u);
    ASSERT_EQ(scene->instances.size(), 2u);            // placed twice
    EXPECT_NEAR(scene->bounds.lower.x, -1.0f, 1e-6f);  // the first Translate was undone
    EXPECT_NEAR(scene->bounds.upper.z, 5.0f, 1e-6f);
    EXPECT_NEAR(scene->instances[1].ApplyPoint(Vec3(0.0f)).z, 5.0f, 1e-6f);
}

TEST(PbrtLoaderTest, MotionIsRenderedAtTheStartTimeAndWarnedOnce) {
    // killeroo-moving: a shape whose StartTime and EndTime transforms differ is placed at its
    // start-time transform (pbrt-v4's time 0), with one warning naming the directive; an
    // EndTime transform equal to the start's moves nothing and says nothing.
    const std::string moving =
        "AttributeBegin\nActiveTransform StartTime\nTranslate 30 0 0\nActiveTransform All\n"
        "Translate 0 2 0\n" +
        std::string(kQuad) + kQuad + "AttributeEnd\n";
    std::vector<std::string> warnings;
    const absl::StatusOr<Scene> scene = Load(Bundle(moving), &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_NEAR(scene->bounds.lower.x, 29.0f, 1e-5f);  // the quad's -1, moved by 30 and 0
    EXPECT_NEAR(scene->bounds.lower.y, 1.0f, 1e-5f);
    int motion = 0;
    for (const std::string& warning : warnings)
        motion += warning.find("Shape: motion blur is left out") != std::string::npos;
    EXPECT_EQ(motion, 1) << "once, however many shapes move";

    const std::string still =
        "ActiveTransform StartTime\nTranslate 1 0 0\nActiveTransform EndTime\nTranslate 1 0 0\n"
        "ActiveTransform All\n" +
        std::string(kQuad) +
        "TransformBegin\nActiveTransform EndTime\nTranslate 0 0 5\nTransformEnd\n"
        "ActiveTransform All\n" +
        kQuad;
    warnings.clear();
    ASSERT_TRUE(Load(Bundle(still), &warnings).ok());
    EXPECT_FALSE(Contains(warnings, "motion blur")) << "TransformEnd restores both times";

    SceneBundle camera = Bundle(kQuad);
    camera.files["scene.pbrt"] = "ActiveTransform EndTime\nTranslate 0 0 1\nActiveTransform All\n" +
                                 camera.files["scene.pbrt"];
    warnings.clear();
    ASSERT_TRUE(Load(camera, &warnings).ok());
    EXPECT_TRUE(Contains(warnings, "Camera: motion blur is left out"));
}

TEST(PbrtLoaderTest, EmittingShapesOfAnObjectArePlacedAsWorldTriangles) {
    const std::string world =
        std::string("ObjectBegin \"lamp\"\n") + kQuad +
        "AttributeBegin\nTranslate 0 0 1\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" + kQuad +
        "AttributeEnd\nObjectEnd\nObjectInstance \"lamp\"\nTranslate 3 0 0\nObjectInstance "
        "\"lamp\"\n";
    const absl::StatusOr<Scene> scene = Load(Bundle(world));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->prototypes.size(), 1u);
    EXPECT_EQ(scene->prototypes[0].triangle_count, 2u);  // the plain quad
    EXPECT_EQ(scene->instances.size(), 2u);
    ASSERT_EQ(scene->WorldTriangleCount(), 4u);  // the emitting quad, once per instance
    for (uint32_t t = 0; t < scene->WorldTriangleCount(); ++t)
        EXPECT_TRUE(scene->materials[scene->triangles[t].material].IsEmissive());
    EXPECT_NEAR(scene->bounds.upper.x, 4.0f, 1e-6f);
}

TEST(PbrtLoaderTest, InstanceLimitAndSingularInstancesAreRefused) {
    const std::string object = std::string("ObjectBegin \"quad\"\n") + kQuad + "ObjectEnd\n";
    SceneLoadOptions options;
    options.limits.max_instances = 1;
    const absl::StatusOr<Scene> limited =
        LoadScene(Bundle(object + "ObjectInstance \"quad\"\nObjectInstance \"quad\"\n"),
                  "scenes/scene.pbrt", options);
    ExpectError(limited,
                "scenes/scene.pbrt:10:1: ObjectInstance \"quad\": the scene would hold more than 1 "
                "instances");
    EXPECT_EQ(limited.status().code(), absl::StatusCode::kResourceExhausted);
    ExpectError(Load(Bundle(object + "Scale 1 0 1\nObjectInstance \"quad\"\n")),
                "transform is singular");
}

TEST(PbrtLoaderTest, AreaLightsEmitFromTheirShapesFront) {
    // A 2x2 square facing +z with L = 2; "power" P scales L by P / (pi x area), as pbrt-v4
    // does whatever L's colour: 8 pi / (pi x 4) = 2, so L = 4.
    const std::string world =
        std::string("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n") + kQuad +
        "AttributeEnd\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2] \"float "
        "power\" " +
        std::to_string(8 * kPiD) + "\nTranslate 0 0 1\nReverseOrientation\n" + kQuad +
        "AttributeEnd\n";
    const absl::StatusOr<Scene> scene = Load(Bundle(world));
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(scene->triangles.size(), 4u);
    const Triangle& plain = scene->triangles[0];
    const Triangle& reversed = scene->triangles[2];
    EXPECT_NEAR(scene->materials[plain.material].emission.x, 2.0f, 1e-6f);
    EXPECT_NEAR(plain.normal.z, 1.0f, 1e-6f);
    EXPECT_NEAR(scene->materials[reversed.material].emission.x, 4.0f, 1e-5f);
    EXPECT_NEAR(reversed.normal.z, -1.0f, 1e-6f);  // ReverseOrientation flips the emitting side
}

TEST(PbrtLoaderTest, QuadricsAreTessellatedFaithfully) {
    const absl::StatusOr<Scene> sphere = Load(Bundle("Shape \"sphere\" \"float radius\" 2\n"));
    ASSERT_TRUE(sphere.ok()) << sphere.status();
    EXPECT_NEAR(TotalArea(*sphere), 4 * kPiD * 4,
                4 * kPiD * 4 * 2e-3);  // 4 pi r^2 within the facets' shortfall
    for (const Triangle& t : sphere->triangles) {
        const Vec3 centre = (sphere->positions[t.vertex[0]] + sphere->positions[t.vertex[1]] +
                             sphere->positions[t.vertex[2]]) /
                            3.0f;
        ASSERT_GT(Dot(t.normal, centre), 0.0f) << "sphere triangles face outward";
        ASSERT_TRUE(t.smooth);
    }
    const absl::StatusOr<Scene> disk = Load(Bundle(
        "Shape \"disk\" \"float radius\" 1 \"float innerradius\" 0.5 \"float height\" 0.25\n"));
    ASSERT_TRUE(disk.ok()) << disk.status();
    EXPECT_NEAR(TotalArea(*disk), kPiD * 0.75, kPiD * 0.75 * 2e-3);
    for (const Triangle& t : disk->triangles) EXPECT_NEAR(t.normal.z, 1.0f, 1e-5f);
    EXPECT_NEAR(disk->bounds.upper.z, 0.25f, 1e-6f);
    const absl::StatusOr<Scene> cylinder =
        Load(Bundle("Shape \"cylinder\" \"float radius\" 0.5 \"float zmin\" 0 \"float zmax\" 2\n"));
    ASSERT_TRUE(cylinder.ok()) << cylinder.status();
    EXPECT_NEAR(TotalArea(*cylinder), 2 * kPiD * 0.5 * 2, 2 * kPiD * 0.5 * 2 * 2e-3);  // 2 pi r h
    for (const Triangle& t : cylinder->triangles) {
        const Vec3 centre = (cylinder->positions[t.vertex[0]] + cylinder->positions[t.vertex[1]] +
                             cylinder->positions[t.vertex[2]]) /
                            3.0f;
        ASSERT_GT(t.normal.x * centre.x + t.normal.y * centre.y, 0.0f)
            << "cylinder triangles face outward";
    }
}

TEST(PbrtLoaderTest, CurvedBilinearPatchesFollowTheirSurface) {
    // P(u, v) = (u, v, u v): a saddle. A planar patch beside it stays two triangles.
    const absl::StatusOr<Scene> scene =
        Load(Bundle("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 1]\n"
                    "Shape \"bilinearmesh\" \"point3 P\" [0 0 5  1 0 5  0 1 5  1 1 5]\n"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    size_t flat = 0;
    double area = 0;
    for (const Triangle& t : scene->triangles) {
        const Vec3 a = scene->positions[t.vertex[0]], b = scene->positions[t.vertex[1]],
                   c = scene->positions[t.vertex[2]];
        if (a.z == 5.0f) {
            ++flat;
            continue;
        }
        area += 0.5 * Length(Cross(Vec3d(b - a), Vec3d(c - a)));
        for (const uint32_t v : t.vertex) {
            const Vec3 p = scene->positions[v];
            EXPECT_NEAR(p.z, p.x * p.y, 1e-6f);
            // The surface's normal there, cross(dP/du, dP/dv) = (-v, -u, 1), normalised.
            const Vec3 n = Normalize(Vec3(-p.y, -p.x, 1));
            EXPECT_NEAR(Dot(scene->normals[v], n), 1.0f, 1e-5f);
        }
        EXPECT_TRUE(t.smooth);
        EXPECT_GT(t.normal.z, 0.0f) << "facing as the patch's corners wind";
    }
    EXPECT_EQ(flat, 2u);
    // The saddle's area, the integral of |(-v, -u, 1)| over the unit square, against the
    // facets' (within 0.1%: the grid's cells lie within 0.125% of the patch's size from it).
    double exact = 0;
    constexpr int kSteps = 1000;
    for (int i = 0; i < kSteps; ++i)
        for (int j = 0; j < kSteps; ++j) {
            const double u = (i + 0.5) / kSteps, v = (j + 0.5) / kSteps;
            exact += std::sqrt(1 + u * u + v * v) / (kSteps * kSteps);
        }
    EXPECT_NEAR(area, exact, exact * 1e-3);
}

TEST(PbrtLoaderTest, IncludesPlyMeshesAndImageTexturesComeFromTheBundle) {
    // A binary PLY quad (two triangles after triangulation) and a 2x1 PNG: red, then grey.
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float "
        "y\n"
        "property float z\nproperty float u\nproperty float v\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float vertices[4][5] = {
        {-1, -1, 0, 0, 0}, {1, -1, 0, 1, 0}, {1, 1, 0, 1, 1}, {-1, 1, 0, 0, 1}};
    ply.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
    const unsigned char count = 4;
    const int32_t face[4] = {0, 1, 2, 3};
    ply.append(reinterpret_cast<const char*>(&count), 1);
    ply.append(reinterpret_cast<const char*>(face), sizeof face);
    const std::string png = TwoTexelPng({255, 0, 0, 128, 128, 128}, "photonfarm-pbrt-texture.png");
    ASSERT_FALSE(png.empty());
    const std::string world = "Include \"parts/wall.pbrt\"\n";
    // "unused" names a file the bundle lacks: no material uses it, so it is never read.
    const std::string wall =
        "Texture \"unused\" \"spectrum\" \"imagemap\" \"string filename\" \"textures/absent.png\"\n"
        "Texture \"checks\" \"spectrum\" \"imagemap\" \"string filename\" \"textures/two.png\" "
        "\"float uscale\" 2\n"
        "Material \"diffuse\" \"texture reflectance\" \"checks\"\n"
        "Shape \"plymesh\" \"string filename\" \"meshes/./quad.ply\"\n";
    const SceneBundle bundle = Bundle(
        world, {{"parts/wall.pbrt", wall}, {"meshes/quad.ply", ply}, {"textures/two.png", png}});
    const absl::StatusOr<Scene> scene = Load(bundle);
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->triangles.size(), 2u);
    ASSERT_EQ(scene->textures.size(), 1u);
    EXPECT_NEAR(scene->textures[0]->texels[0].x, 1.0f, 1e-6f);
    EXPECT_NEAR(scene->textures[0]->texels[1].x, SrgbToLinear(128 / 255.0f),
                1e-6f);  // sRGB decoded
    // pbrt's v runs up the image and uscale 2 repeats it twice: the vertex at uv (1, 1) maps to (2,
    // 0).
    bool found = false;
    for (size_t v = 0; v < scene->positions.size(); ++v)
        if (scene->positions[v].x > 0.5f && scene->positions[v].y > 0.5f) {
            EXPECT_NEAR(scene->uvs[v].x, 2.0f, 1e-6f);
            EXPECT_NEAR(scene->uvs[v].y, 0.0f, 1e-6f);
            found = true;
        }
    EXPECT_TRUE(found);
}

TEST(PbrtLoaderTest, UnsupportedThingsWarnAtTheirLocation) {
    std::vector<std::string> warnings;
    const std::string world =
        std::string("Shape \"sphere\" \"float radius\" 1 \"float bogus\" 3\n") +
        "Shape \"hyperboloid\"\nMakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n";
    SceneBundle bundle = Bundle(world);
    bundle.files["scene.pbrt"] =
        "PixelFilter \"gaussian\" \"float sigma\" 0.5\n" + bundle.files["scene.pbrt"];
    const absl::StatusOr<Scene> scene = Load(bundle, &warnings);
    ASSERT_TRUE(scene.ok()) << scene.status();
    // The parameter's own line and column: line 7 (the filter and 5 lines of preamble before it).
    EXPECT_TRUE(Contains(
        warnings, "scenes/scene.pbrt:7:33: warning: Shape \"sphere\": parameter \"float bogus\""));
    EXPECT_TRUE(Contains(warnings,
                         "scenes/scene.pbrt:8:1: warning: Shape \"hyperboloid\" is not supported"));
    EXPECT_TRUE(Contains(warnings, "MakeNamedMedium"));
    EXPECT_FALSE(Contains(warnings, "PixelFilter")) << "the filter is the camera's";
}

TEST(PbrtLoaderTest, PixelFilterIsTheCamerasWithPbrtsDefaults) {
    const auto with = [](const std::string& filter) {
        SceneBundle bundle = Bundle(kQuad);
        bundle.files["scene.pbrt"] = filter + "\n" + bundle.files["scene.pbrt"];
        return Load(bundle);
    };
    // None given: pbrt-v4's Gaussian, radius 1.5 and sigma 0.5.
    const absl::StatusOr<Scene> plain = Load(Bundle(kQuad));
    ASSERT_TRUE(plain.ok()) << plain.status();
    EXPECT_EQ(plain->camera.filter.kind, FilterKind::kGaussian);
    EXPECT_EQ(plain->camera.filter.radius_x, 1.5f);
    EXPECT_EQ(plain->camera.filter.sigma, 0.5f);
    const absl::StatusOr<Scene> triangle = with("PixelFilter \"triangle\"");
    ASSERT_TRUE(triangle.ok()) << triangle.status();
    EXPECT_EQ(triangle->camera.filter.kind, FilterKind::kTriangle);
    EXPECT_EQ(triangle->camera.filter.radius_y, 2.0f);
    const absl::StatusOr<Scene> mitchell =
        with("PixelFilter \"mitchell\" \"float xradius\" 1 \"float B\" 0.5 \"float C\" 0.25");
    ASSERT_TRUE(mitchell.ok()) << mitchell.status();
    EXPECT_EQ(mitchell->camera.filter.kind, FilterKind::kMitchell);
    EXPECT_EQ(mitchell->camera.filter.radius_x, 1.0f);
    EXPECT_EQ(mitchell->camera.filter.radius_y, 2.0f);
    EXPECT_EQ(mitchell->camera.filter.b, 0.5f);
    EXPECT_EQ(mitchell->camera.filter.c, 0.25f);
    const absl::StatusOr<Scene> sinc = with("PixelFilter \"sinc\" \"float tau\" 2");
    ASSERT_TRUE(sinc.ok()) << sinc.status();
    EXPECT_EQ(sinc->camera.filter.radius_x, 4.0f);
    EXPECT_EQ(sinc->camera.filter.tau, 2.0f);
    // pbrt-v3's form: widths that are radii, and the Gaussian's alpha (sigma = 1 / sqrt(2 alpha)).
    std::vector<std::string> warnings;
    SceneBundle v3 = Bundle(kQuad);
    v3.files["scene.pbrt"] =
        "PixelFilter \"gaussian\" \"float xwidth\" 2 \"float ywidth\" 1 \"float alpha\" 2\n" +
        v3.files["scene.pbrt"];
    const absl::StatusOr<Scene> old = Load(v3, &warnings);
    ASSERT_TRUE(old.ok()) << old.status();
    EXPECT_EQ(old->camera.filter.radius_x, 2.0f);
    EXPECT_EQ(old->camera.filter.radius_y, 1.0f);
    EXPECT_FLOAT_EQ(old->camera.filter.sigma, 0.5f);
    EXPECT_TRUE(Contains(warnings, "read as a pbrt-v3 file"));
    // Refused, naming the place.
    ExpectError(with("PixelFilter \"lanczos\""),
                "scenes/scene.pbrt:1:1: PixelFilter \"lanczos\": not a filter");
    ExpectError(with("PixelFilter \"box\" \"float xradius\" 0"),
                "scenes/scene.pbrt:1:1: PixelFilter \"box\": radius 0");
    ExpectError(with("PixelFilter \"gaussian\" \"float alpha\" -1"), "\"alpha\" must be positive");
    ExpectError(Load(Bundle("PixelFilter \"box\"\n" + std::string(kQuad))),
                "PixelFilter: must come before WorldBegin");
}

TEST(PbrtLoaderTest, BadInputIsAOneLineErrorNamingFileLineAndColumn) {
    ExpectError(Load(Bundle("Shapee \"sphere\"\n")),
                "scenes/scene.pbrt:6:1: unknown directive 'Shapee'");
    ExpectError(Load(Bundle("Shape \"sphere\" \"float radius\" \"big\"\n")),
                "scenes/scene.pbrt:6:16");
    ExpectError(Load(Bundle("Shape \"sphere\" \"float radius\" -1\n")),
                "\"float radius\" must be positive");
    ExpectError(Load(Bundle("Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer "
                            "indices\" [0 1 7]\n")),
                "index 2 (7) is outside the 3 points");
    ExpectError(Load(Bundle("Material \"velvet\"\n")),
                "scenes/scene.pbrt:6:1: Material \"velvet\" is unknown");
    ExpectError(Load(Bundle("NamedMaterial \"nothing\"\n")), "no material named \"nothing\"");
    ExpectError(Load(Bundle("AttributeEnd\n")), "AttributeEnd without AttributeBegin");
    ExpectError(Load(Bundle("Translate 1 2\n")), "Translate needs 3 numbers");
    ExpectError(Load(Bundle("Include \"../outside.pbrt\"\n")), "leaves the scene's folder");
    ExpectError(Load(Bundle("Include \"/etc/passwd\"\n")), "is absolute");
    ExpectError(Load(Bundle("Include \"missing.pbrt\"\n")),
                "scenes/scene.pbrt:6:1: 'missing.pbrt' is not in the scene bundle");
    ExpectError(Load(Bundle("Include \"loop.pbrt\"\n", {{"loop.pbrt", "Include \"loop.pbrt\"\n"}})),
                "includes nest deeper than");
    ExpectError(Load(Bundle("Include\n")),
                "scenes/scene.pbrt:6:1: Include needs a quoted file name after it");
    // An include's error stands, not what its directive makes of the stream's end.
    ExpectError(Load(Bundle("Shape \"trianglemesh\" Include \"missing.pbrt\"\n")),
                "scenes/scene.pbrt:6:22: 'missing.pbrt' is not in the scene bundle");
    ExpectError(Load(Bundle("Shape \"plymesh\" \"string filename\" \"bad.ply\"\n",
                            {{"bad.ply", "ply\nformat nonsense\n"}})),
                "bad.ply: PLY header line 2: \"format\" needs an encoding and a version");
    ExpectError(
        Load(Bundle(
            std::string("Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\"\n"
                        "Material \"diffuse\" \"texture reflectance\" \"t\"\n") +
                kQuad,
            {{"t.png", "not a png"}})),
        "scenes/scene.pbrt:6:1: Texture \"t\": t.png");
    SceneBundle no_light = Bundle(kQuad);
    std::string& main = no_light.files["scene.pbrt"];
    main.erase(main.find("LightSource"), std::strlen("LightSource \"point\" \"rgb I\" [1 1 1]\n"));
    ExpectError(Load(no_light), "scene has no light");
}

TEST(PbrtLoaderTest, FilmAndShutterGiveTheImagingRatio) {
    // pbrt-v4: exposure time (shutterclose - shutteropen) x iso / 100, and the white balance.
    const auto load = [](const std::string& camera, const std::string& film) {
        SceneBundle bundle = Bundle(kQuad);
        std::string& main = bundle.files["scene.pbrt"];
        main.replace(main.find("Camera \"perspective\" \"float fov\" 40"),
                     std::strlen("Camera \"perspective\" \"float fov\" 40"),
                     "Camera \"perspective\" \"float fov\" 40 " + camera);
        main.replace(main.find("Film \"rgb\""), std::strlen("Film \"rgb\""),
                     "Film \"rgb\" " + film);
        std::vector<std::string> warnings;
        absl::StatusOr<Scene> scene = Load(bundle, &warnings);
        return std::make_pair(std::move(scene), warnings);
    };
    const auto [plain, none] = load("", "");
    ASSERT_TRUE(plain.ok()) << plain.status();
    EXPECT_TRUE(plain->film.IsIdentity());
    const auto [bright, ignored] = load("\"float shutterclose\" 0.5", "\"float iso\" 800");
    ASSERT_TRUE(bright.ok()) << bright.status();
    EXPECT_EQ(bright->film.Apply(Rgb(1.0f)), Rgb(4.0f));
    const auto [balanced, warnings] =
        load("", "\"float whitebalance\" 5000 \"string sensor\" \"nikon_d850\"");
    ASSERT_TRUE(balanced.ok()) << balanced.status();
    EXPECT_FALSE(balanced->film.IsIdentity());
    EXPECT_TRUE(Contains(warnings, "sensor \"nikon_d850\": its spectral response is not modelled"));
    ExpectError(load("", "\"float iso\" -5").first, "\"iso\" must lie in (0, 1e7)");
    ExpectError(load("", "\"float whitebalance\" 1000").first, "[4000, 25000]");
    ExpectError(load("\"float shutteropen\" 1 \"float shutterclose\" 0.5", "").first,
                "\"shutterclose\" must come after \"shutteropen\"");
}

TEST(PbrtLoaderTest, AnotherCameraIsRefused) {
    SceneLoadOptions options;
    options.camera = "top";
    const absl::StatusOr<Scene> scene = LoadScene(Bundle(kQuad), "scenes/scene.pbrt", options);
    ExpectError(scene, "--camera top: scenes/scene.pbrt is a pbrt scene, with one camera");
}

TEST(PbrtLoaderTest, LimitsRefuseOversizedScenes) {
    SceneLoadOptions options;
    options.limits.max_triangles = 100;
    const absl::StatusOr<Scene> scene =
        LoadScene(Bundle("Shape \"sphere\"\n"), "scene.pbrt", options);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(scene.status().message().find("more than 100 triangles"), std::string::npos)
        << scene.status();
}

TEST(PbrtLoaderTest, PackingGathersIncludedMeshesAndNothingElse) {
    const absl::StatusOr<SceneBundle> bundle =
        PackSceneBundle(std::string(PF_SOURCE_DIR) + "/scenes/pbrt/cornell-box.pbrt");
    ASSERT_TRUE(bundle.ok()) << bundle.status();
    std::vector<std::string> paths;
    for (const auto& [path, contents] : bundle->files) paths.push_back(path);
    EXPECT_EQ(paths, (std::vector<std::string>{"cornell-box.pbrt", "cornell-room.pbrt",
                                               "meshes/tall-block.ply"}));
    const absl::StatusOr<Scene> scene = LoadScene(*bundle, "cornell-box.pbrt");
    ASSERT_TRUE(scene.ok()) << scene.status();
    // 5 walls and the light: 12 (the red wall's measured corners lie 0.4% of its size out of
    // one plane: two triangles are within 0.1% of its bilinear surface); two blocks of 5 quads:
    // 20.
    EXPECT_EQ(scene->triangles.size(), 32u);
}

TEST(PbrtLoaderTest, ShippedScenesLoadWithoutWarnings) {
    for (const char* name : {"cornell-box", "cornell-glass", "cornell-glossy", "caustic-glass",
                             "furnace", "furnace-glass", "sky-courtyard", "cornell-stained",
                             "cornell-lamps", "cornell-bumpy", "cornell-materials"}) {
        std::vector<std::string> warnings;
        SceneLoadOptions options;
        options.warnings = &warnings;
        const absl::StatusOr<Scene> scene =
            LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/pbrt/" + name + ".pbrt", options);
        ASSERT_TRUE(scene.ok()) << scene.status();
        EXPECT_TRUE(warnings.empty()) << name << ": " << warnings.front();
    }
}

}  // namespace
}  // namespace pf
