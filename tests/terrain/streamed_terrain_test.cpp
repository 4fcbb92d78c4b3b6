// The streamed terrain's tile wants (terrain/streamed_terrain.h): the frame's selection and the
// look-ahead poses' are made side by side when a task runner is given; the wants are the same
// as made one after another on the frame thread, frame after frame (the ones that redo the
// look-ahead included).
#include <cmath>
#include <vector>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/log.h"
#include "core/task_runner.h"
#include "streaming/open_tile_source.h"
#include "terrain/streamed_terrain.h"
#include "tests/terrain/zion_tiles.h"

namespace vegstream::terrain {
namespace {

struct Pose {
  SelectionView selection;
  EyeView eye;
};

Pose poseAt(const geo::LocalFrame& frame, double lat, double lon, double heightM, const glm::dvec3& look) {
  const double fov = 55.0 * 3.14159265358979 / 180.0;
  const glm::dvec3 at = frame.toLocal({lat, lon, heightM});
  const glm::dvec3 dir = glm::normalize(look);
  const glm::dmat4 vp =
      glm::perspective(fov, 1920.0 / 1080.0, 1.0, 1e6) * glm::lookAt(at, at + dir, glm::dvec3(0.0, 0.0, 1.0));
  return {SelectionView{at, vp, 1080.0, fov},
          EyeView::lookAlong(at, dir, glm::dvec3(0.0, 0.0, 1.0), fov, 1920.0, 1080.0, 1.0)};
}

TEST(StreamedTerrainWants, LookAheadSelectionsOnWorkersGiveTheSameWants) {
  test::ZionTiles& z = test::ZionTiles::get();
  const datasets::DatasetMeta& meta = z.meta();
  const geo::GeoBounds& b = meta.bounds;
  const geo::LocalFrame frame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});
  auto wantsOverAFlight = [&](TaskRunner* tasks) {
    auto source = streaming::openTileSource(z.dir().string(), {});
    EXPECT_TRUE(source.ok());
    streaming::TileStreamer streamer(*source, meta, streamingOptionsFor(meta, {}), makeNullLogger());
    StreamedTerrainOptions o;
    o.roam.tasks = tasks;
    StreamedTerrain terrain(streamer, frame, o);
    std::vector<std::vector<streaming::TileWant>> all;
    for (int i = 0; i < 9; ++i) {  // flying north-east and down; the look-ahead redone every 4th frame
      const double s = 0.004 * i;
      const double lat = b.southDeg + 0.3 * (b.northDeg - b.southDeg) + s, lon = b.westDeg + 0.3 * (b.eastDeg - b.westDeg) + s;
      const Pose now = poseAt(frame, lat, lon, 3000.0 - 150.0 * i, {-1.0, -1.0, -0.6});  // looking back
      std::vector<SelectionView> ahead;
      for (int k = 1; k <= 3; ++k)
        ahead.push_back(poseAt(frame, lat + 0.04 * k, lon + 0.04 * k, 2400.0 - 300.0 * k, {1.0, 1.0, -0.8}).selection);
      all.push_back(terrain.wants(now.selection, now.eye, ahead));
    }
    return all;
  };
  const auto serial = wantsOverAFlight(nullptr);
  ThreadPool pool(3);
  const auto parallel = wantsOverAFlight(&pool);
  ASSERT_EQ(serial.size(), parallel.size());
  size_t lookAhead = 0;
  for (size_t f = 0; f < serial.size(); ++f) {
    ASSERT_EQ(serial[f].size(), parallel[f].size()) << "frame " << f;
    for (size_t i = 0; i < serial[f].size(); ++i) {
      EXPECT_EQ(serial[f][i].key, parallel[f][i].key) << "frame " << f << ", want " << i;
      EXPECT_EQ(serial[f][i].priority, parallel[f][i].priority);
      EXPECT_EQ(serial[f][i].lookAhead, parallel[f][i].lookAhead);
      lookAhead += serial[f][i].lookAhead ? 1 : 0;
    }
  }
  EXPECT_GT(lookAhead, 0u) << "the look-ahead poses want tiles of their own";
}

}  // namespace
}  // namespace vegstream::terrain
