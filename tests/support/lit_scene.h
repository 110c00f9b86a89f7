// A shipped scene (scenes/) loaded with its lights, an Embree scene over it and what it uses,
// for the integration tests that drive the photon and light passes directly.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "core/scene/emitters.h"
#include "core/scene/scene_features.h"
#include "core/scene_io/scene_loader.h"
#include "embree/embree_tracer.h"

namespace pf::testing {

// The emitters keep a reference to the scene, so all of it stays together, at a fixed address.
struct LitScene {
    Scene scene;
    std::unique_ptr<Emitters> emitters;
    std::unique_ptr<embree::EmbreeTracer> tracer;
    SceneFeatures features;  // AnalyseFeatures
};

// scenes/`name` loaded; null, with a test failure, where it fails to load.
inline std::unique_ptr<const LitScene> LoadLitScene(const std::string& name) {
    absl::StatusOr<Scene> scene = LoadScene(std::string(PF_SOURCE_DIR) + "/scenes/" + name);
    EXPECT_TRUE(scene.ok()) << scene.status();
    if (!scene.ok()) return nullptr;
    auto lit = std::make_unique<LitScene>();
    lit->scene = std::move(*scene);
    lit->emitters = std::make_unique<Emitters>(lit->scene);
    auto tracer = embree::EmbreeTracer::Create(lit->scene);
    EXPECT_TRUE(tracer.ok()) << tracer.status();
    if (!tracer.ok()) return nullptr;
    lit->tracer = std::move(*tracer);
    lit->features = AnalyseFeatures(lit->scene, *lit->emitters);
    return lit;
}

}  // namespace pf::testing
