// Frames in flight (scene/frame_driver.h, scene/playback.h) in-process, on a generated dataset
// and lavapipe: the driver keeps up to three frames in flight and hands their records back in
// submission order, refusing a fourth submit, a collect out of order and run() with frames in
// flight (without losing anything); a playback that keeps three frames in flight gives the same
// counts and the same images as the serial one, with wall_ms one figure per frame; validation
// stays silent throughout.

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

class FramePipelineTest : public testing::SceneFrameTest {
 protected:
  // One playback of benchmark-30s at 1 fps (31 frames, 2 warm-up frames) keeping `depth` frames
  // in flight, every 5th frame saved under dir/frames<tag>.
  Recording play(std::size_t depth, const std::string& tag) {
    auto scene = open();  // a fresh scene each time: nothing carried over but the inputs
    EXPECT_TRUE(scene);
    if (!scene) return {};
    FrameDriver driver(*scene);
    PlaybackOptions po;
    po.fps = 1.0;
    po.warmupS = 2.0;
    po.framesInFlight = depth;
    po.framesEvery = 5;
    po.framesDir = dir / ("frames" + tag);
    fs::create_directories(po.framesDir);
    auto rec = playFlight(driver, path(*scene), po);
    EXPECT_TRUE(rec.ok()) << rec.error().message;
    EXPECT_EQ(driver.framesInFlight(), 0u) << "playback collects every frame it submits";
    return rec.ok() ? std::move(*rec) : Recording{};
  }

};

bool isTimeColumn(const std::string& name) { return name.size() > 3 && name.substr(name.size() - 3) == "_ms"; }

std::string readBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST_F(FramePipelineTest, ThreeInFlightComeBackInOrderAndMistakesAreRefused) {
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
    return in;
  };
  ASSERT_EQ(FrameDriver::kMaxInFlight, 3u) << "three frame slots (render/frame_slots.h)";
  EXPECT_FALSE(driver.collect(1).ok()) << "nothing is in flight";

  std::vector<uint64_t> indices;
  for (double t : {1.0, 2.0, 3.0}) {
    auto index = driver.submit(inputAt(t));
    ASSERT_TRUE(index.ok()) << index.error().message;
    indices.push_back(*index);
  }
  EXPECT_EQ(driver.framesInFlight(), 3u);
  EXPECT_EQ(indices[1], indices[0] + 1);
  EXPECT_EQ(indices[2], indices[0] + 2);
  EXPECT_EQ(driver.oldestInFlight(), indices[0]);

  // A fourth would take the oldest frame's slot before its figures were collected.
  auto fourth = driver.submit(inputAt(4.0));
  EXPECT_FALSE(fourth.ok());
  if (!fourth.ok()) {
    EXPECT_EQ(fourth.error().kind, ErrorKind::Internal);
  }
  EXPECT_FALSE(driver.run(inputAt(4.0)).ok()) << "run() is refused while frames are in flight";
  // Out of order, or an index that never was: refused, and nothing is dropped.
  auto early = driver.collect(indices[1]);
  EXPECT_FALSE(early.ok());
  if (!early.ok()) {
    EXPECT_NE(early.error().message.find("oldest first"), std::string::npos) << early.error().message;
  }
  EXPECT_FALSE(driver.collect(indices[2] + 7).ok());
  EXPECT_EQ(driver.framesInFlight(), 3u);

  for (std::size_t k = 0; k < 3; ++k) {
    auto r = driver.collect(indices[k]);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->index, indices[k]);
    EXPECT_DOUBLE_EQ(r->timeS, 1.0 + static_cast<double>(k)) << "the record of the frame submitted k-th";
    EXPECT_GT(r->terrainTriangles, 0u);
    EXPECT_TRUE(std::isfinite(r->gpu.frameMs));
    EXPECT_EQ(driver.framesInFlight(), 2u - k);
  }
  // With the queue empty the driver works as before.
  auto after = driver.run(inputAt(5.0));
  ASSERT_TRUE(after.ok()) << after.error().message;
  EXPECT_EQ(after->index, indices[2] + 1) << "the refused submit made no frame";
}

TEST_F(FramePipelineTest, ThreeInFlightGiveTheSameCountsAndImagesAsOne) {
  const Recording serial = play(1, "1");
  const Recording piped = play(3, "3");
  EXPECT_EQ(serial.framesInFlight, 1u);
  EXPECT_EQ(piped.framesInFlight, 3u);
  EXPECT_EQ(serial.warmupFrames, 2u);
  const flight::RecordTable& a = serial.table;
  const flight::RecordTable& b = piped.table;
  ASSERT_EQ(a.rowCount(), flight::frameCount(30.0, 1.0));
  ASSERT_EQ(b.rowCount(), a.rowCount());
  ASSERT_EQ(a.columns().size(), b.columns().size());
  std::size_t compared = 0;
  for (std::size_t c = 0; c < a.columns().size(); ++c) {
    const std::string& name = a.columns()[c].name;
    ASSERT_EQ(name, b.columns()[c].name);
    if (isTimeColumn(name)) continue;
    for (std::size_t i = 0; i < a.rowCount(); ++i) {
      if (std::isnan(a.at(i, c)) && std::isnan(b.at(i, c))) continue;
      EXPECT_EQ(a.at(i, c), b.at(i, c)) << name << " differs in frame " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, 50u);  // every count column of frames.csv
  // Rows are in frame order, each frame at its own time; the flight drew terrain and plants.
  const auto frames = b.values(*b.find("frame"));
  for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i], static_cast<double>(i));
  EXPECT_GT(b.values(*b.find("terrain_triangles")).front(), 100.0);
  // Every frame has its own wall and CPU figures (no speed is asserted, only what they mean).
  for (const char* column : {"wall_ms", "cpu_frame_ms", "cpu_record_submit_ms"})
    for (double v : b.values(*b.find(column))) {
      EXPECT_TRUE(std::isfinite(v)) << column;
      EXPECT_GE(v, 0.0) << column;
    }
  // wall_ms runs from one completion to the next: the intervals do not overlap, so with frames
  // in flight they add up to no more than the whole playback (a per-frame submit-to-collect
  // time would count the overlapped time up to three times).
  for (const Recording* r : {&serial, &piped}) {
    double sum = 0.0;
    for (double v : r->table.values(*r->table.find("wall_ms"))) sum += v;
    EXPECT_LE(sum, r->wallS * 1000.0) << "frames in flight: " << r->framesInFlight;
  }

  ASSERT_EQ(serial.pngFrames, 7u);  // frames 0, 5, …, 30
  ASSERT_EQ(piped.pngFrames, 7u);
  for (const auto& entry : fs::directory_iterator(dir / "frames1")) {
    const fs::path other = dir / "frames3" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    const std::string da = readBytes(entry.path()), db = readBytes(other);
    EXPECT_GT(da.size(), 100u);
    EXPECT_TRUE(da == db) << entry.path().filename() << " differs between 1 and 3 frames in flight";
  }
}

}  // namespace
}  // namespace vegstream::scene
