#pragma once
// What the scene's tests share: a 3 km synthetic dataset made once per build of the test program
// (cachedFixture), and a Scene opened over it on lavapipe with the validation layers on, their
// messages collected in `validation` for the test to check.

#include <cstdint>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "scene/scene.h"
#include "tests/support/test_dirs.h"

namespace vegstream::scene::testing {

inline Result<std::filesystem::path> syntheticDataset() {
  return vegstream::testing::cachedFixture(
      "scene-synthetic-3km", vegstream::testing::programKey(), [](const std::filesystem::path& dir) -> Status {
        datasets::SyntheticOptions o;
        o.out = dir;
        o.sizeKm = 3.0;
        o.seed = 5;
        datasets::NullProgress progress;
        auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
        if (!meta.ok()) return meta.error();
        return {};
      });
}

struct SceneRequest {
  StreamingMode mode = StreamingMode::Settled;
  uint64_t cpuBudgetBytes = 64ull << 20;
  uint32_t width = 160, height = 90;
};

// The scene over `dataset`, validated; null (and a test failure) when it cannot be opened.
inline std::unique_ptr<Scene> openValidatedScene(const std::filesystem::path& dataset, const SceneRequest& request,
                                                 const std::shared_ptr<render::ValidationLog>& validation) {
  SceneOptions o;
  o.dataset = dataset.string();
  o.mode = request.mode;
  o.streaming.cpuBudgetBytes = request.cpuBudgetBytes;
  o.renderer.width = request.width;
  o.renderer.height = request.height;
  o.renderer.msaa = 1;
  o.renderer.context.validate = true;
  o.renderer.context.validationLog = validation;
  auto scene = Scene::open(o);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

}  // namespace vegstream::scene::testing
