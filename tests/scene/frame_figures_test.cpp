// The frame's figures as the stages declare them (scene/frame_figures.h): frames.csv's column
// order, the sections' place, one column per name, a unit for each; a record's cells. No GPU.

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {
namespace {

std::vector<std::string> names(const FigureLayout& layout) {
  std::vector<std::string> out;
  for (const flight::RecordColumn& c : frameColumns(layout)) out.push_back(c.name);
  return out;
}

TEST(FrameFigures, ColumnsInTheDocumentedOrder) {
  const std::vector<std::string> n = names({{"sky", "Terrain pass"}, true});
  const auto at = [&](const std::string& name) { return std::find(n.begin(), n.end(), name) - n.begin(); };
  EXPECT_EQ(n.front(), "frame");
  EXPECT_EQ(at("pitch_deg"), 7);
  EXPECT_EQ(at("cpu_flight_ms"), at("pitch_deg") + 1);
  EXPECT_EQ(at("cpu_record_submit_ms"), at("cpu_simulation_ms") + 1);
  EXPECT_EQ(at("cpu_frame_ms"), at("cpu_record_submit_ms") + 1);
  EXPECT_EQ(at("gpu_sky_ms"), at("gpu_frame_ms") + 1);
  EXPECT_EQ(at("gpu_terrain_pass_ms"), at("gpu_frame_ms") + 2);
  EXPECT_EQ(at("wall_ms"), at("gpu_terrain_pass_ms") + 1);
  EXPECT_EQ(at("gpu_bytes"), at("stat_fragment_invocations") + 2);
  EXPECT_EQ(at("streaming_wait_ms"), at("gpu_bytes") + 1);  // issue 5's columns follow
  EXPECT_EQ(at("stream_lookahead_wants"), at("stream_wanted_resident") + 1);
  EXPECT_EQ(at("terrain_roam_update_ms"), at("terrain_error_relaxation") + 1);  // issue 6's columns follow
  // Issue 17's terrain rasterised in compute follows, then issue 7's columns.
  EXPECT_EQ(at("terrain_raster_triangles"), at("terrain_achieved_error_px") + 1);
  EXPECT_EQ(at("plant_seed_triangles"), at("terrain_depth_edge_tiles") + 1);
  EXPECT_EQ(at("plant_cull_tested"), at("plant_triangles") + 1);  // issue 17's occlusion culling follows
  EXPECT_EQ(at("trees_full"), at("plants_culled") + 1);           // issue 20's trees follow
  EXPECT_EQ(at("tree_tiles_wanted"), at("trees_classified") + 1);
  EXPECT_GT(at("sun_azimuth_deg"), at("tree_placement_ms"));  // issue 39's sun follows, last
  EXPECT_EQ(at("sun_azimuth_deg"), static_cast<long>(n.size()) - 2);
  EXPECT_EQ(n.back(), "sun_elevation_deg");
}

TEST(FrameFigures, EveryColumnOnceWithAUnit) {
  const FrameFigures figures = frameFigures({{"sky", "terrain"}, true});
  std::set<std::string> seen;
  for (const FrameFigure& f : figures) {
    EXPECT_TRUE(seen.insert(f.column.name).second) << f.column.name;
    EXPECT_FALSE(f.column.unit.empty()) << f.column.name;
    EXPECT_TRUE(f.value) << f.column.name;
  }
  EXPECT_TRUE(std::is_sorted(figures.begin(), figures.end(),
                             [](const FrameFigure& a, const FrameFigure& b) { return a.section < b.section; }));
}

TEST(FrameFigures, ARecordsCellsAndTheFiguresItHasNot) {
  FrameRecord r;
  r.row = 4;
  r.timeS = 0.25;
  r.scene.streaming.requestsIssued = 7;
  r.gpu.passes = {{"sky", 1.5}};
  const FigureLayout layout{{"sky"}, true};
  const flight::RecordTable table = frameTable({r}, layout);
  ASSERT_EQ(table.rowCount(), 1u);
  const auto cell = [&](const char* name) { return table.at(0, *table.find(name)); };
  EXPECT_EQ(cell("frame"), 4.0);
  EXPECT_EQ(cell("t_s"), 0.25);
  EXPECT_EQ(cell("stream_requests_issued"), 7.0);
  EXPECT_EQ(cell("gpu_sky_ms"), 1.5);
  // No plants, no trees, no compute raster, not recorded: empty cells.
  for (const char* empty : {"plants", "trees_full", "tree_tiles_wanted", "terrain_raster_triangles", "png_ms"})
    EXPECT_TRUE(std::isnan(cell(empty))) << empty;
  EXPECT_TRUE(std::isnan(frameTable({r}, FigureLayout{{"sky"}, false}).at(0, *table.find("gpu_sky_ms"))));
  // The HUD's lookup reads the same declarations.
  const FigureLookup lookup(layout);
  EXPECT_EQ(lookup(r, "stream_requests_issued"), 7.0);
}

}  // namespace
}  // namespace vegstream::scene
