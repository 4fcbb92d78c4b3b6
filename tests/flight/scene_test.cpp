// A dataset opened for flying: the loaded mesh agrees with the dataset's own heights, the
// camera points where the flight sample says, and the frame renders with validation silent.

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "datasets/dataset_reader.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "flight/scene.h"

namespace vegstream::flight {
namespace {
namespace fs = std::filesystem;

fs::path syntheticDataset() {
  const fs::path dir = fs::path(VEGSTREAM_TEST_TMP) / "scene-dataset";
  if (!fs::exists(dir / "dataset.json")) {
    fs::remove_all(dir);
    datasets::SyntheticOptions o;
    o.out = dir;
    o.sizeKm = 3.0;
    o.seed = 5;
    datasets::NullProgress progress;
    auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
    EXPECT_TRUE(meta.ok()) << meta.error().message;
  }
  return dir;
}

class SceneTest : public ::testing::Test {
 protected:
  std::shared_ptr<render::ValidationLog> validation = std::make_shared<render::ValidationLog>();
  std::unique_ptr<Scene> open(uint64_t maxTriangles) {
    SceneOptions o;
    o.dataset = syntheticDataset();
    o.renderer.width = 160;
    o.renderer.height = 90;
    o.renderer.msaa = 1;
    o.renderer.context.validate = true;
    o.renderer.context.validationLog = validation;
    o.maxMeshTriangles = maxTriangles;
    auto scene = Scene::open(o);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : nullptr;
  }
  void TearDown() override {
    for (const auto& m : validation->messages()) ADD_FAILURE() << "validation: " << m;
  }
};

TEST_F(SceneTest, GroundHeightsMatchTheDatasetAtTheLoadedZoom) {
  auto scene = open(200'000);
  ASSERT_TRUE(scene);
  const SceneInfo& info = scene->info();
  EXPECT_LE(info.meshTriangles, 200'000u);
  EXPECT_GT(info.meshTriangles, 20'000u);
  EXPECT_GT(info.gpuBytes, info.meshTriangles * 3 * 4);  // at least the indices
  auto reader = datasets::DatasetReader::open(syntheticDataset());
  ASSERT_TRUE(reader.ok());
  const geo::GeoBounds& b = info.bounds;
  int compared = 0;
  for (int i = 1; i < 10; ++i)
    for (int j = 1; j < 10; ++j) {
      const double lat = b.southDeg + (b.northDeg - b.southDeg) * i / 10.0;
      const double lon = b.westDeg + (b.eastDeg - b.westDeg) * j / 10.0;
      auto expected = reader->heightAtZoom(lat, lon, info.heightZoom);
      ASSERT_TRUE(expected.ok());
      const double h = scene->groundHeight(lat, lon);
      ASSERT_FALSE(std::isnan(h));
      EXPECT_NEAR(h, *expected, 0.05) << lat << ", " << lon;
      ++compared;
    }
  EXPECT_EQ(compared, 81);
  EXPECT_TRUE(std::isnan(scene->groundHeight(b.northDeg + 1.0, b.westDeg)));
}

TEST_F(SceneTest, CameraFollowsHeadingAndPitchAndTheFrameRenders) {
  auto scene = open(100'000);
  ASSERT_TRUE(scene);
  const geo::GeoBounds& b = scene->info().bounds;
  FlightSample s;
  s.position = {0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0};
  s.position.heightM = scene->groundHeight(s.position.latDeg, s.position.lonDeg) + 300.0;
  s.headingDeg = 90.0;  // east
  s.pitchDeg = -20.0;
  render::FrameRequest req = scene->frameRequest(s);
  EXPECT_NEAR(req.camera.forward.x, std::cos(20.0 * M_PI / 180.0), 1e-3);
  EXPECT_NEAR(req.camera.forward.y, 0.0, 1e-3);
  EXPECT_NEAR(req.camera.forward.z, -std::sin(20.0 * M_PI / 180.0), 1e-3);
  EXPECT_NEAR(glm::length(req.camera.position - scene->frame().toLocal(s.position)), 0.0, 1e-6);
  req.readbackDepth = true;
  auto frame = scene->renderer().renderFrame(req);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  EXPECT_EQ(frame->terrainTriangles, scene->info().meshTriangles);
  // Looking 20° down from 300 m: the bottom of the image is ground, nearer than 2 km.
  const float bottom = frame->depth->depth[size_t{89} * 160 + 80];
  EXPECT_GT(bottom, render::reverseZDepth(req.camera, 2000.0));
}

}  // namespace
}  // namespace vegstream::flight
