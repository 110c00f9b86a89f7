// The caustic probe: light reaching diffuse surfaces through specular chains is found where
// it exists and not claimed where walls stop it.
#include "core/ppm/caustic_probe.h"

#include <gtest/gtest.h>

#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "tests/support/gltf_builder.h"

namespace pf {
namespace {

CausticProbe Probe(const Scene& scene) {
    const Emitters emitters(scene);
    absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
        embree::EmbreeTracer::Create(scene);
    EXPECT_TRUE(tracer.ok()) << tracer.status();
    return ProbeCaustics(scene, emitters, **tracer, 1);
}

TEST(CausticProbeTest, GlassUnderTheLightCastsCaustics) {
    const absl::StatusOr<Scene> scene =
        LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/cornell-glass.gltf");
    ASSERT_TRUE(scene.ok()) << scene.status();
    const CausticProbe probe = Probe(*scene);
    EXPECT_EQ(probe.paths, 1u << 14);
    EXPECT_GT(probe.caustic, 100u);  // the spheres take several percent of the light
}

TEST(CausticProbeTest, AMirrorTheLightCannotSeeCastsNone) {
    // The lit quad (the light above it faces down onto its top), and a mirror below it facing
    // away from the light: no light path meets the mirror before a diffuse surface.
    testing::TestScene scene = testing::LitQuadScene();
    testing::TestMaterial mirror{Rgb(0.9f), Rgb(0.0f)};
    mirror.metallic = 1, mirror.roughness = 0;  // glTF's perfect mirror
    mirror.extra = R"(,"doubleSided":true)";    // a material of its own: no single-sided copy
    scene.materials.push_back(mirror);
    scene.meshes.push_back({{{-0.5f, -0.5f, -1}, {0.5f, 0.5f, -1}, {0.5f, -0.5f, -1}}, 2});
    const absl::StatusOr<Scene> loaded = LoadScene(testing::WriteGltf(scene, "hidden-mirror.gltf"));
    ASSERT_TRUE(loaded.ok()) << loaded.status();
    // The mirror is the last triangle (the open quads' materials gain single-sided copies).
    EXPECT_EQ(loaded->materials[loaded->triangles.back().material].type, MaterialType::kMirror);
    EXPECT_EQ(Probe(*loaded).caustic, 0u);
}

}  // namespace
}  // namespace pf
