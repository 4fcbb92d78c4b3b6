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
#include "flight/path_templates.h"
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

// A test that plays frames over the synthetic dataset: its own output directory, a validated
// 96 × 54 scene, the benchmark-30s path over it; any validation message fails the test.
class SceneFrameTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = vegstream::testing::testOutputDir();
    auto made = syntheticDataset();
    ASSERT_TRUE(made.ok()) << made.error().message;
    dataset = *made;
  }
  void TearDown() override {
    for (const auto& m : validation->messages()) ADD_FAILURE() << "validation: " << m;
  }
  std::unique_ptr<Scene> open() { return openValidatedScene(dataset, {.width = 96, .height = 54}, validation); }
  flight::FlightPath path(const Scene& scene) {
    auto p = flight::makePathFromTemplate("benchmark-30s", scene.info().bounds, scene.groundFunction());
    EXPECT_TRUE(p.ok()) << p.error().message;
    return p.ok() ? *p : flight::FlightPath{};
  }

  std::filesystem::path dir, dataset;
  std::shared_ptr<render::ValidationLog> validation = std::make_shared<render::ValidationLog>();
};

}  // namespace vegstream::scene::testing
