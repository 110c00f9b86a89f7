// Instancing (pbrt's ObjectBegin/ObjectInstance; glTF meshes several nodes use): prototypes
// stored once and placed by Embree instances must be the scene they stand for. Rays find the
// same surfaces as in the scene with every instance expanded, and the instanced scene renders
// the image of the same scene written without instances, on the CPU (Embree's two-level BVH)
// and on Vulkan (which expands instances into its one BVH).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/mesh_builder.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"
#include "tests/support/image_agreement.h"
#include "tests/support/small_render.h"
#include "tests/support/test_env.h"
#include "tests/support/vulkan_validation.h"

namespace pf {
namespace {

// A block of white quads with a glass ball (a PLY mesh) on top, in the object's own space.
constexpr char kBlock[] =
    "    NamedMaterial \"white\"\n"
    "    Shape \"bilinearmesh\" \"point3 P\" [ -0.08 0.12 -0.08  0.08 0.12 -0.08  -0.08 0.12 0.08  "
    "0.08 0.12 0.08 ]"
    " \"integer indices\" [ 0 1 2 3 ]\n"
    "    Shape \"bilinearmesh\" \"point3 P\" [ -0.08 0 -0.08  -0.08 0.12 -0.08  0.08 0 -0.08  0.08 "
    "0.12 -0.08 ]"
    " \"integer indices\" [ 0 1 2 3 ]\n"
    "    Shape \"bilinearmesh\" \"point3 P\" [ 0.08 0 -0.08  0.08 0.12 -0.08  0.08 0 0.08  0.08 "
    "0.12 0.08 ]"
    " \"integer indices\" [ 0 1 2 3 ]\n"
    "    Shape \"bilinearmesh\" \"point3 P\" [ -0.08 0 0.08  -0.08 0.12 0.08  -0.08 0 -0.08  -0.08 "
    "0.12 -0.08 ]"
    " \"integer indices\" [ 0 1 2 3 ]\n"
    "    AttributeBegin\n"
    "        Material \"dielectric\" \"float eta\" 1.5\n"
    "        Translate 0 0.12 0\n"
    "        Scale 0.1 0.1 0.1\n"
    "        Shape \"plymesh\" \"string filename\" \"glass-sphere.ply\"\n"
    "    AttributeEnd\n";

// A mirror ball, one of pbrt's own spheres.
constexpr char kBall[] =
    "    Material \"conductor\" \"rgb reflectance\" [ 0.9 0.9 0.9 ]\n"
    "    Shape \"sphere\" \"float radius\" 0.04\n";

struct Placement {
    const char* object;
    const char* transform;
};

// The blocks moved, turned and mirrored, squashed; the balls moved, turned and stretched. (pbrt
// settles a quadric's front with the transform where it is defined, so a mirrored instance of
// a sphere is not the sphere written out under the mirror: no mirrored ball here.)
constexpr Placement kPlacements[] = {
    {"block", "Translate 0.15 0 0.15\n"},
    {"block", "Translate 0.4 0 0.3\nRotate 30 0 1 0\nScale -1 1 1\n"},
    {"block", "Translate 0.25 0 0.42\nScale 0.6 1.5 0.6\n"},
    {"ball", "Translate 0.1 0.04 0.35\n"},
    {"ball", "Translate 0.45 0.06 0.1\nRotate 45 1 0 0\nScale 1 1.5 1\n"},
};

// The Cornell room (scenes/pbrt/cornell-room.pbrt) with the blocks and balls, instanced or
// written out.
std::string ObjectsScene(bool instanced) {
    std::string scene =
        "Scale -1 1 1\nLookAt 0.278 0.273 -0.8  0.278 0.273 0.0  0.0 1.0 0.0\n"
        "Camera \"perspective\" \"float fov\" 39.3\nWorldBegin\nInclude \"cornell-room.pbrt\"\n";
    if (instanced)
        scene += std::string("ObjectBegin \"block\"\n") + kBlock +
                 "ObjectEnd\nObjectBegin \"ball\"\n" + kBall + "ObjectEnd\n";
    for (const Placement& placement : kPlacements) {
        const std::string object = placement.object;
        scene += std::string("AttributeBegin\n") + placement.transform +
                 (instanced           ? "ObjectInstance \"" + object + "\"\n"
                  : object == "block" ? kBlock
                                      : kBall) +
                 "AttributeEnd\n";
    }
    return scene;
}

class Instancing : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        folder_ = testing::FreshTempDir("instancing");  // this process's own
        std::filesystem::copy_file(
            std::filesystem::path(PF_SOURCE_DIR) / "scenes/pbrt/cornell-room.pbrt",
            folder_ / "cornell-room.pbrt", std::filesystem::copy_options::overwrite_existing);
        std::filesystem::copy_file(
            std::filesystem::path(PF_SOURCE_DIR) / "scenes/pbrt/meshes/glass-sphere.ply",
            folder_ / "glass-sphere.ply", std::filesystem::copy_options::overwrite_existing);
        std::ofstream(folder_ / "instanced.pbrt") << ObjectsScene(true);
        std::ofstream(folder_ / "written-out.pbrt") << ObjectsScene(false);
    }
    static std::string Path(const std::string& name) { return (folder_ / name).string(); }
    static inline std::filesystem::path folder_;
};

TEST_F(Instancing, ObjectsAreStoredOnceAndPlacedByInstances) {
    const absl::StatusOr<Scene> instanced = LoadScene(Path("instanced.pbrt"));
    ASSERT_TRUE(instanced.ok()) << instanced.status();
    const absl::StatusOr<Scene> written_out = LoadScene(Path("written-out.pbrt"));
    ASSERT_TRUE(written_out.ok()) << written_out.status();
    ASSERT_EQ(instanced->prototypes.size(), 2u);
    EXPECT_EQ(instanced->instances.size(), 5u);
    const uint32_t block = instanced->prototypes[0].triangle_count,
                   ball = instanced->prototypes[1].triangle_count;
    EXPECT_EQ(instanced->triangles.size(), instanced->WorldTriangleCount() + block + ball);
    EXPECT_EQ(written_out->triangles.size(),
              instanced->WorldTriangleCount() + 3 * block + 2 * ball);
    // An instance's bounds are its prototype's box turned: they hold the shapes, a little loosely.
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(instanced->bounds.lower[axis], written_out->bounds.lower[axis] + 1e-6f);
        EXPECT_GE(instanced->bounds.upper[axis], written_out->bounds.upper[axis] - 1e-6f);
        EXPECT_LE(instanced->bounds.Diagonal(), 1.05f * written_out->bounds.Diagonal());
    }
}

// Rays from points all over the room, in every direction, through Embree's instances and
// through the expanded scene's one BVH: the same hits, surfaces and shadows, to float precision
// (a ray grazing an edge may pick the neighbouring triangle: a few in 10^4 may differ).
TEST_F(Instancing, RaysMeetTheSameSurfacesAsInTheExpandedScene) {
    const absl::StatusOr<Scene> scene = LoadScene(Path("instanced.pbrt"));
    ASSERT_TRUE(scene.ok()) << scene.status();
    const absl::StatusOr<Scene> flat = FlattenInstances(*scene, SceneLimits{}.max_triangles);
    ASSERT_TRUE(flat.ok()) << flat.status();
    auto instanced_tracer = embree::EmbreeTracer::Create(*scene);
    auto flat_tracer = embree::EmbreeTracer::Create(*flat);
    ASSERT_TRUE(instanced_tracer.ok() && flat_tracer.ok());
    Rng rng(7);
    constexpr int kRays = 20000;
    int instance_hits = 0, mismatches = 0, packet_mismatches = 0;
    Ray packet[Tracer::kPacketSize];
    RayHit expected[Tracer::kPacketSize];
    bool expected_found[Tracer::kPacketSize];
    for (int i = 0; i < kRays; ++i) {
        Ray ray;
        for (int axis = 0; axis < 3; ++axis) {
            const float u = rng.NextFloat();
            ray.origin[axis] =
                scene->bounds.lower[axis] +
                (0.05f + 0.9f * u) * (scene->bounds.upper[axis] - scene->bounds.lower[axis]);
        }
        const float u1 = rng.NextFloat();
        const float u2 = rng.NextFloat();
        ray.direction = Vec3(SampleUniformSphere(u1, u2));
        RayHit hit, flat_hit;
        const bool found = (*instanced_tracer)->Intersect(ray, &hit);
        const bool flat_found = (*flat_tracer)->Intersect(ray, &flat_hit);
        packet[i % Tracer::kPacketSize] = ray;
        expected[i % Tracer::kPacketSize] = hit;
        expected_found[i % Tracer::kPacketSize] = found;
        if (found != flat_found) {
            ++mismatches;
            continue;
        }
        if (!found) continue;
        instance_hits += hit.instance != Instance::kNone;
        const SurfacePoint a = scene->Surface(hit), b = flat->Surface(flat_hit);
        if (std::abs(hit.t - flat_hit.t) > 1e-4f || a.material != b.material) {
            ++mismatches;
            continue;
        }
        EXPECT_LE(Length(a.position - b.position), 1e-4f);
        EXPECT_GE(Dot(a.geometric_normal, b.geometric_normal), 0.9999f);
        EXPECT_GE(Dot(a.shading_normal, b.shading_normal), 0.999f);
        // Shadow rays toward the hit stop short of it; beyond it, they are blocked.
        Ray shadow = ray;
        shadow.t_max = 0.999f * hit.t;
        EXPECT_EQ((*instanced_tracer)->Occluded(shadow), (*flat_tracer)->Occluded(shadow));
        if (i % Tracer::kPacketSize == Tracer::kPacketSize - 1) {
            const bool active[Tracer::kPacketSize] = {true, true, true, true,
                                                      true, true, true, true};
            RayHit hits[Tracer::kPacketSize];
            bool packet_found[Tracer::kPacketSize];
            (*instanced_tracer)->IntersectPacket(packet, active, hits, packet_found);
            for (int lane = 0; lane < Tracer::kPacketSize; ++lane)
                packet_mismatches +=
                    packet_found[lane] != expected_found[lane] ||
                    (packet_found[lane] && (hits[lane].triangle != expected[lane].triangle ||
                                            hits[lane].instance != expected[lane].instance));
        }
    }
    EXPECT_GT(instance_hits, kRays / 50);  // the blocks are in the way of some rays
    EXPECT_LE(mismatches, kRays / 2000);
    EXPECT_EQ(packet_mismatches, 0);
}

// An object of no shapes (transparent-machines' "single arm 0": transforms only) is placed as
// nothing, as pbrt-v4 places it: the scene loads, Embree builds it, and rays meet only the
// other shapes.
TEST(InstancingEmpty, AnObjectOfNoShapesIsPlacedAsNothing) {
    const std::filesystem::path folder = testing::FreshTempDir("instancing-empty");
    std::ofstream(folder / "scene.pbrt")
        << "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\nWorldBegin\n"
           "LightSource \"point\" \"rgb I\" [1 1 1]\n"
           "ObjectBegin \"empty\"\nAttributeBegin\nTranslate 0 0 1\nAttributeEnd\nObjectEnd\n"
           "ObjectInstance \"empty\"\nTranslate 3 0 0\nObjectInstance \"empty\"\n"
           "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "
           "\"integer indices\" [0 1 2 3]\n";
    const absl::StatusOr<Scene> scene = LoadScene((folder / "scene.pbrt").string());
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->instances.size(), 0u);
    EXPECT_EQ(scene->WorldTriangleCount(), 2u);
    const auto tracer = embree::EmbreeTracer::Create(*scene);
    ASSERT_TRUE(tracer.ok()) << tracer.status();
    // The quad (translated by 3 along x, as the Translate before it says) is hit; where the
    // first instance would be, nothing.
    RayHit hit;
    Ray ray;
    ray.origin = Vec3(3, 0, -2), ray.direction = Vec3(0, 0, 1);
    ASSERT_TRUE((*tracer)->Intersect(ray, &hit));
    EXPECT_NEAR(hit.t, 2.0f, 1e-5f);
    ray.origin = Vec3(0, 0, -2);
    EXPECT_FALSE((*tracer)->Intersect(ray, &hit));
}

TEST_F(Instancing, InstancedSceneRendersTheWrittenOutScenesImage) {
    testing::ExpectSameEstimator(testing::RenderSmall(Path("instanced.pbrt"), "cpu", 3),
                                 testing::RenderSmall(Path("written-out.pbrt"), "cpu", 1),
                                 testing::RenderSmall(Path("written-out.pbrt"), "cpu", 2));
}

TEST_F(Instancing, VulkanExpandsInstancesIntoTheSameImage) {
    testing::SkipWithoutVulkan();
    if (IsSkipped() || HasFatalFailure()) return;
    const unsigned long long errors_before = testing::VulkanValidationErrors();
    testing::ExpectSameEstimator(testing::RenderSmall(Path("instanced.pbrt"), "vulkan", 3),
                                 testing::RenderSmall(Path("instanced.pbrt"), "cpu", 1),
                                 testing::RenderSmall(Path("instanced.pbrt"), "cpu", 2));
    EXPECT_EQ(testing::VulkanValidationErrors(), errors_before);
}

}  // namespace
}  // namespace pf
