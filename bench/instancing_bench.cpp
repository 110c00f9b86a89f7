// What instancing buys and costs on the CPU: the Cornell room with a grid of 12 x 12 balls
// (the 9024-triangle PLY sphere of scenes/pbrt/meshes), written once with ObjectInstance and
// once expanded (FlattenInstances, what the Vulkan backend traces). Google Benchmark times the
// Embree build and single-thread random rays of each; after the table, the ratios instanced /
// expanded of geometry memory, build time and ray rate.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/mesh_builder.h"
#include "core/scene_io/scene_files.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf {
namespace {

constexpr int kGrid = 12;

Scene LoadBallsScene() {
    const std::string folder = std::string(PF_SOURCE_DIR) + "/scenes/pbrt/";
    SceneBundle bundle;
    bundle.main_file = "balls.pbrt";
    for (const char* file : {"cornell-room.pbrt", "meshes/glass-sphere.ply"})
        bundle.files[file] = std::string(*ReadWholeFile(folder + file));
    std::string scene =
        "Scale -1 1 1\nLookAt 0.278 0.273 -0.8  0.278 0.273 0.0  0.0 1.0 0.0\nCamera "
        "\"perspective\" \"float fov\" 39.3\n"
        "WorldBegin\nInclude \"cornell-room.pbrt\"\nObjectBegin \"ball\"\nNamedMaterial \"white\"\n"
        "Scale 0.04 0.04 0.04\nShape \"plymesh\" \"string filename\" "
        "\"meshes/glass-sphere.ply\"\nObjectEnd\n";
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j)
            absl::StrAppend(&scene, "AttributeBegin\nTranslate ", 0.03 + 0.045 * i, " 0 ",
                            0.03 + 0.045 * j, "\nObjectInstance \"ball\"\nAttributeEnd\n");
    bundle.files[bundle.main_file] = scene;
    absl::StatusOr<Scene> loaded = LoadScene(bundle, bundle.main_file);
    if (!loaded.ok()) {
        std::fprintf(stderr, "instancing_bench: %s\n",
                     std::string(loaded.status().message()).c_str());
        std::exit(1);
    }
    return std::move(*loaded);
}

const Scene& Balls(bool instanced) {
    static const Scene kInstanced = LoadBallsScene();
    static const Scene kExpanded = *FlattenInstances(kInstanced, SceneLimits{}.max_triangles);
    return instanced ? kInstanced : kExpanded;
}

size_t GeometryBytes(const Scene& scene) {
    return scene.positions.size() * sizeof(Vec3) + scene.normals.size() * sizeof(Vec3) +
           scene.uvs.size() * sizeof(Point2) + scene.triangles.size() * sizeof(Triangle) +
           scene.instances.size() * sizeof(Instance);
}

std::map<std::string, double> g_figures;

const char* Name(bool instanced) { return instanced ? "instanced" : "expanded"; }

void BM_EmbreeBuild(benchmark::State& state, bool instanced) {
    const Scene& scene = Balls(instanced);
    double seconds = 0;
    int64_t builds = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        auto tracer = embree::EmbreeTracer::Create(scene);
        benchmark::DoNotOptimize(tracer);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++builds;
    }
    state.counters["triangles"] = double(scene.triangles.size());
    g_figures[absl::StrCat("build/", Name(instanced))] = seconds / builds;
}

void BM_EmbreeRandomRays(benchmark::State& state, bool instanced) {
    const Scene& scene = Balls(instanced);
    auto tracer = std::move(*embree::EmbreeTracer::Create(scene));
    // The same rays for both: from points in the lower half of the room (among the balls),
    // in every direction.
    const Bounds& bounds = Balls(true).bounds;
    Rng rng(7);
    std::vector<Ray> rays(1 << 16);
    for (Ray& ray : rays) {
        for (int axis = 0; axis < 3; ++axis) {
            const float u = rng.NextFloat();
            const float extent = axis == 1 ? 0.1f : 1.0f;
            ray.origin[axis] =
                bounds.lower[axis] + extent * u * (bounds.upper[axis] - bounds.lower[axis]);
        }
        const float u1 = rng.NextFloat();
        const float u2 = rng.NextFloat();
        ray.direction = Vec3(SampleUniformSphere(u1, u2));
    }
    uint64_t traced = 0, hits = 0;
    double seconds = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        hits += tracer->CountHits(rays);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        traced += rays.size();
    }
    state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
    state.counters["hit fraction"] = double(hits) / double(traced);
    g_figures[absl::StrCat("rays/", Name(instanced))] = traced / seconds;
}

}  // namespace
}  // namespace pf

int main(int argc, char** argv) {
    // One thread for the ray rate (Embree's build uses TBB: also one, for a like-for-like ratio).
    tbb::global_control single_thread(tbb::global_control::max_allowed_parallelism, 1);
    for (bool instanced : {true, false}) {
        benchmark::RegisterBenchmark(absl::StrCat("BM_EmbreeBuild/", pf::Name(instanced)).c_str(),
                                     pf::BM_EmbreeBuild, instanced)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(1.0);
        benchmark::RegisterBenchmark(
            absl::StrCat("BM_EmbreeRandomRays/", pf::Name(instanced)).c_str(),
            pf::BM_EmbreeRandomRays, instanced)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(1.0);
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    const pf::Scene& instanced = pf::Balls(true);
    const pf::Scene& expanded = pf::Balls(false);
    std::printf("\n%d balls of %u triangles: %zu triangles stored instanced, %zu expanded\n",
                pf::kGrid * pf::kGrid, instanced.prototypes.at(0).triangle_count,
                instanced.triangles.size(), expanded.triangles.size());
    std::printf("instanced over expanded: geometry memory %.3f",
                double(pf::GeometryBytes(instanced)) / double(pf::GeometryBytes(expanded)));
    auto& figures = pf::g_figures;
    if (figures["build/expanded"] > 0)
        std::printf(", Embree build time %.3f",
                    figures["build/instanced"] / figures["build/expanded"]);
    if (figures["rays/expanded"] > 0)
        std::printf(", random rays/s %.3f", figures["rays/instanced"] / figures["rays/expanded"]);
    std::printf("\n");
    return 0;
}
