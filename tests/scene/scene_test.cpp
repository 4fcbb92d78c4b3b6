// A dataset opened for flying: the ground model agrees with the dataset's own heights, the
// camera points where the flight sample says, frames stream their tiles (settled: all resident,
// realtime: never waiting) and render with validation silent.

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "datasets/dataset_reader.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "scene/scene.h"
#include "tests/scene/scene_fixture.h"
#include "tests/support/test_dirs.h"

namespace vegstream::scene {
using namespace vegstream::flight;
namespace {
namespace fs = std::filesystem;

using testing::syntheticDataset;

class SceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dataset = syntheticDataset();
    ASSERT_TRUE(dataset.ok()) << dataset.error().message;
    dataset_ = *dataset;
  }
  fs::path dataset_;
  std::shared_ptr<render::ValidationLog> validation = std::make_shared<render::ValidationLog>();
  std::unique_ptr<Scene> open(StreamingMode mode = StreamingMode::Settled, uint64_t cpuBudget = 64ull << 20) {
    return testing::openValidatedScene(dataset_, {mode, cpuBudget}, validation);
  }
  void TearDown() override {
    for (const auto& m : validation->messages()) ADD_FAILURE() << "validation: " << m;
  }
  FlightSample overCentre(const Scene& scene, double heightAboveGround, double headingDeg, double pitchDeg) {
    const geo::GeoBounds& b = scene.info().bounds;
    FlightSample s;
    s.position = {0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0};
    s.position.heightM = scene.groundHeight(s.position.latDeg, s.position.lonDeg) + heightAboveGround;
    s.headingDeg = headingDeg;
    s.pitchDeg = pitchDeg;
    return s;
  }
};

TEST_F(SceneTest, GroundHeightsMatchTheDatasetAtTheGroundZoom) {
  auto scene = open();
  ASSERT_TRUE(scene);
  const SceneInfo& info = scene->info();
  EXPECT_EQ(info.groundZoom, info.maxZoom);  // a 3 km dataset fits the ground mosaic at full resolution
  EXPECT_TRUE(info.hasImagery);
  EXPECT_GT(info.imageryLayers, 0u);
  auto reader = datasets::DatasetReader::open(dataset_);
  ASSERT_TRUE(reader.ok());
  const geo::GeoBounds& b = info.bounds;
  int compared = 0;
  for (int i = 1; i < 10; ++i)
    for (int j = 1; j < 10; ++j) {
      const double lat = b.southDeg + (b.northDeg - b.southDeg) * i / 10.0;
      const double lon = b.westDeg + (b.eastDeg - b.westDeg) * j / 10.0;
      auto expected = reader->heightAtZoom(lat, lon, info.groundZoom);
      ASSERT_TRUE(expected.ok());
      const double h = scene->groundHeight(lat, lon);
      ASSERT_FALSE(std::isnan(h));
      EXPECT_NEAR(h, *expected, 0.05) << lat << ", " << lon;
      ++compared;
    }
  EXPECT_EQ(compared, 81);
  EXPECT_TRUE(std::isnan(scene->groundHeight(b.northDeg + 1.0, b.westDeg)));
}

TEST_F(SceneTest, CameraFollowsHeadingAndPitchAndASettledFrameDrawsOnlyWantedTiles) {
  auto scene = open();
  ASSERT_TRUE(scene);
  const FlightSample s = overCentre(*scene, 300.0, 90.0, -20.0);  // east, 20° down
  render::FrameRequest req = scene->prepareFrame(s, 0.0);
  EXPECT_NEAR(req.camera.forward.x, std::cos(20.0 * M_PI / 180.0), 1e-3);
  EXPECT_NEAR(req.camera.forward.y, 0.0, 1e-3);
  EXPECT_NEAR(req.camera.forward.z, -std::sin(20.0 * M_PI / 180.0), 1e-3);
  EXPECT_NEAR(glm::length(req.camera.position - scene->frame().toLocal(s.position)), 0.0, 1e-6);
  const SceneFrameFigures& fig = scene->lastFrameFigures();
  EXPECT_GT(fig.terrain.pieces, 0u);
  EXPECT_EQ(fig.terrain.fallbackPieces, 0u) << "settled: every wanted tile is resident";
  EXPECT_EQ(fig.streaming.wantedResident, fig.streaming.wanted);
  EXPECT_EQ(fig.uploads, fig.streaming.tilesResidentGpu);  // the first frame uploads every imagery tile it draws
  EXPECT_EQ(req.terrain.size(), fig.terrain.pieces);
  req.readbackDepth = true;
  req.readbackColor = true;
  auto frame = scene->renderer().renderFrame(req);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  EXPECT_EQ(frame->terrainTriangles, fig.terrain.triangles);
  // Looking 20° down from 300 m: the bottom of the image is ground, nearer than 2 km.
  const float bottom = frame->depth->depth[size_t{89} * 160 + 80];
  EXPECT_GT(bottom, render::reverseZDepth(req.camera, 2000.0));

  // Determinism: a second scene on the same dataset draws the same pieces and the same image.
  auto again = open();
  ASSERT_TRUE(again);
  render::FrameRequest req2 = again->prepareFrame(s, 0.0);
  req2.readbackColor = true;
  auto frame2 = again->renderer().renderFrame(req2);
  ASSERT_TRUE(frame2.ok());
  EXPECT_EQ(frame2->terrainTriangles, frame->terrainTriangles);
  EXPECT_EQ(frame2->color->rgba, frame->color->rgba);
}

TEST_F(SceneTest, RealtimeFramesNeverWaitAndFillInAsTilesArrive) {
  auto scene = open(StreamingMode::Realtime);
  ASSERT_TRUE(scene);
  double t = 0.0;
  int frame = 0;
  // Renders one realtime frame; returns the request's draws' morph / blend extremes.
  auto step = [&](const FlightSample& s, bool& allResident, bool& morphing, bool& blending) {
    const auto start = std::chrono::steady_clock::now();
    render::FrameRequest req = scene->prepareFrame(s, t);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const SceneFrameFigures& fig = scene->lastFrameFigures();
    EXPECT_EQ(fig.settleWaitMs, 0.0);
    EXPECT_LT(ms, 1000.0) << "a realtime frame must not wait for I/O";
    // ROAM morphs its vertices on the CPU: the figures count the drawn ones still morphing.
    morphing = morphing || fig.terrain.roam.morphingVertices > 0;
    for (const render::TerrainDraw& d : req.terrain)
      blending = blending || (d.imageryBlend > 0.0f && d.imageryBlend < 1.0f && d.previousLayer >= 0);
    auto result = scene->renderer().renderFrame(req);
    EXPECT_TRUE(result.ok()) << result.error().message;
    // "Settled" also needs ROAM to have stopped refining: a split made now morphs for 0.5 s (on
    // a slow build — sanitizers — the per-frame work budget spreads refinement over more frames).
    allResident = fig.streaming.wantedResident == fig.streaming.wanted && fig.terrain.fallbackPieces == 0 &&
                  fig.terrain.pieces > 0 && fig.terrain.roam.splits == 0 && fig.terrain.roam.merges == 0;
    t += 1.0 / 60.0;
    ++frame;
    return req;
  };

  // High above: the coarse tiles stream in; the first frame cannot have them yet (and ROAM
  // refines from its root triangles).
  bool resident = false, morphing = false, blending = false;
  const FlightSample high = overCentre(*scene, 6000.0, 0.0, -60.0);
  step(high, resident, morphing, blending);
  EXPECT_FALSE(resident) << "the first realtime frame cannot have its tiles already";
  // No sleeping between frames: each frame is the work under test, and the tiles come from
  // worker threads at the machine's pace, so the loops are bounded by wall time, not a count
  // of frames (two test processes share the cores).
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (!resident && Clock::now() < deadline) step(high, resident, morphing, blending);
  ASSERT_TRUE(resident) << "the wanted tiles never all arrived";

  // Down low: nodes split and finer tiles arrive; each fades in over half a second of flight
  // time (geometry morphs from the coarse surface, imagery blends over the layer drawn before).
  const FlightSample low = overCentre(*scene, 150.0, 0.0, -30.0);
  morphing = blending = false;
  int lastArrival = frame;
  while (frame - lastArrival < 45 && Clock::now() < deadline) {
    bool allHere = false;
    step(low, allHere, morphing, blending);
    if (!allHere) lastArrival = frame;
  }
  EXPECT_TRUE(morphing) << "finer heights arrived, so some geometry morphed";
  EXPECT_TRUE(blending) << "finer imagery arrived, so some imagery blended";
  ASSERT_GE(frame - lastArrival, 45) << "tiles kept arriving or ROAM kept refining";
  // Over 0.5 s after the last arrival or refinement: everything drawn at the fine data.
  bool unused = false, stillMorphing = false, stillBlending = false;
  render::FrameRequest last = step(low, unused, stillMorphing, stillBlending);
  EXPECT_EQ(scene->lastFrameFigures().terrain.roam.morphingVertices, 0u);
  for (const render::TerrainDraw& d : last.terrain) EXPECT_EQ(d.imageryBlend, 1.0f);
}

}  // namespace
}  // namespace vegstream::scene
