// The frame driver (scene/frame_driver.h) in-process, on a generated dataset and lavapipe:
// fixed-step playback gives the same counts and the same images run after run; a frame split
// into submit and collect (the window's overlap) gives the same record as run(); the
// simulation's CPU figure is filled every frame; validation stays silent.

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "flight/path_templates.h"
#include "scene/frame_driver.h"
#include "scene/playback.h"
#include "tests/scene/scene_fixture.h"
#include "tests/support/test_dirs.h"

namespace vegstream::scene {
namespace {
namespace fs = std::filesystem;

class FrameDriverTest : public testing::SceneFrameTest {
};

bool isTimeColumn(const std::string& name) { return name.size() > 3 && name.substr(name.size() - 3) == "_ms"; }

TEST_F(FrameDriverTest, PlaybackTwiceGivesTheSameCountsAndImages) {
  std::vector<flight::RecordTable> tables;
  std::vector<fs::path> frameDirs;
  for (int run = 0; run < 2; ++run) {
    auto scene = open();  // a fresh scene each time: nothing carried over but the inputs
    ASSERT_TRUE(scene);
    FrameDriver driver(*scene);
    PlaybackOptions po;
    po.fps = 1.0;
    po.framesEvery = 10;
    po.framesDir = dir / ("frames" + std::to_string(run));
    fs::create_directories(po.framesDir);
    auto rec = playFlight(driver, path(*scene), po);
    ASSERT_TRUE(rec.ok()) << rec.error().message;
    EXPECT_EQ(rec->table.rowCount(), flight::frameCount(30.0, 1.0));
    EXPECT_EQ(rec->pngFrames, 4u);
    tables.push_back(std::move(rec->table));
    frameDirs.push_back(po.framesDir);
  }
  const flight::RecordTable& a = tables[0];
  const flight::RecordTable& b = tables[1];
  ASSERT_EQ(a.columns().size(), b.columns().size());
  std::size_t compared = 0;
  for (std::size_t c = 0; c < a.columns().size(); ++c) {
    const std::string& name = a.columns()[c].name;
    if (isTimeColumn(name) || name == "stream_longest_wait_ms") continue;
    ASSERT_EQ(a.rowCount(), b.rowCount());
    for (std::size_t i = 0; i < a.rowCount(); ++i) {
      if (std::isnan(a.at(i, c)) && std::isnan(b.at(i, c))) continue;
      EXPECT_EQ(a.at(i, c), b.at(i, c)) << name << " differs in frame " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, 50u);  // every count column of frames.csv
  // Terrain and plants were drawn: the comparison is of a real flight, not of empty frames.
  const auto triangles = a.values(*a.find("terrain_triangles"));
  EXPECT_GT(triangles.front(), 100.0);
  // The simulation steps every frame (with no wind it moves nothing): its CPU time is filled.
  for (double v : a.values(*a.find("cpu_simulation_ms"))) EXPECT_TRUE(std::isfinite(v) && v >= 0.0);

  for (const auto& entry : fs::directory_iterator(frameDirs[0])) {
    const fs::path other = frameDirs[1] / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    std::ifstream fa(entry.path(), std::ios::binary), fb(other, std::ios::binary);
    const std::string da((std::istreambuf_iterator<char>(fa)), {}), db((std::istreambuf_iterator<char>(fb)), {});
    EXPECT_FALSE(da.empty());
    EXPECT_TRUE(da == db) << entry.path().filename() << " differs between the two runs";
  }
}

TEST_F(FrameDriverTest, SubmitThenCollectGivesTheSameRecordAsRun) {
  auto scene = open();
  ASSERT_TRUE(scene);
  const flight::FlightPath p = path(*scene);
  const flight::PathSampler sampler(p);
  FrameDriver driver(*scene);
  auto inputAt = [&](double t) {
    FrameInput in;
    in.timeS = t;
    in.pose = sampler.sample(t, scene->groundFunction());
    in.ahead = flight::lookAheadSamples(sampler, scene->groundFunction(), t);
    in.readbackColor = true;
    return in;
  };
  // Warm the streamer and ROAM up at t = 0 so both ways start from the same state.
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(driver.run(inputAt(0.0)).ok());
  auto whole = driver.run(inputAt(0.0));
  ASSERT_TRUE(whole.ok()) << whole.error().message;

  // Two frames in flight, collected oldest first, as the window does.
  auto first = driver.submit(inputAt(0.0));
  ASSERT_TRUE(first.ok());
  auto second = driver.submit(inputAt(0.0));
  ASSERT_TRUE(second.ok());
  EXPECT_EQ(driver.framesInFlight(), 2u);
  auto one = driver.collect(*first);
  auto two = driver.collect(*second);
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_EQ(driver.framesInFlight(), 0u);
  EXPECT_EQ(one->index + 1, two->index);
  for (const FrameRecord* r : {&*one, &*two}) {
    EXPECT_EQ(r->terrainTriangles, whole->terrainTriangles);
    EXPECT_EQ(r->scene.terrain.roam.leaves, whole->scene.terrain.roam.leaves);
    EXPECT_EQ(r->scene.terrain.roam.seedTriangles, whole->scene.terrain.roam.seedTriangles);
    ASSERT_TRUE(r->color && whole->color);
    EXPECT_TRUE(r->color->rgba == whole->color->rgba);
    EXPECT_TRUE(std::isfinite(r->simulationMs));
    EXPECT_GE(r->driverMs, 0.0);
    EXPECT_GT(r->cpuMs(), 0.0);
  }
}

}  // namespace
}  // namespace vegstream::scene
