// The columns of frames.csv (frame_columns.h), in file order; README.md "Recordings" documents each.

#include "flight/frame_columns.h"

namespace vegstream::flight {

std::string gpuPassColumn(const std::string& pass) {
  std::string out = "gpu_";
  for (char ch : pass) {
    const char c = (ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch;
    out += ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) ? c : '_';
  }
  return out + "_ms";
}

namespace {

// The counts, memory and streaming columns after png_ms.
void addStreamingColumns(std::vector<RecordColumn>& c) {
  for (const char* n : {"terrain_triangles", "stat_input_primitives", "stat_clipping_primitives",
                        "stat_fragment_invocations", "cpu_bytes", "gpu_bytes"})
    c.push_back({n, 0});
  c.push_back({"streaming_wait_ms", 4});       // settled mode's wait, left out of the frame time
  c.push_back({"stream_longest_wait_ms", 1});  // oldest wanted tile not resident yet
  for (const char* n : {"stream_requests_issued",
                        "stream_requests_completed",
                        "stream_requests_cancelled",
                        "stream_requests_failed",
                        "stream_requests_missing",
                        "stream_retries",
                        "stream_bytes_read",
                        "stream_uploads",
                        "stream_upload_bytes",
                        "stream_evictions_cpu",
                        "stream_evictions_gpu",
                        "stream_tiles_resident_cpu",
                        "stream_tiles_resident_gpu",
                        "stream_bytes_resident_cpu",
                        "stream_bytes_resident_gpu",
                        "stream_requests_in_flight",
                        "stream_wanted",
                        "stream_wanted_resident",
                        "stream_lookahead_wants",
                        "terrain_pieces",
                        "terrain_fallback_pieces",
                        "terrain_max_levels_coarser",
                        "terrain_meshes_built"})
    c.push_back({n, 0});
}

// The terrain's error and ROAM columns, the compute raster's, the plants', the Hi-Z culling's and
// the trees'.
void addTerrainAndPlantColumns(std::vector<RecordColumn>& c) {
  c.push_back({"terrain_error_bound_px", 3});
  c.push_back({"terrain_error_relaxation", 3});
  c.push_back({"terrain_roam_update_ms", 6});
  c.push_back({"terrain_roam_output_ms", 6});
  c.push_back({"terrain_roam_compact_wait_ms", 6});
  c.push_back({"terrain_roam_priorities_ms", 6});
  c.push_back({"terrain_roam_split_ms", 6});
  for (const char* n : {"terrain_leaves", "terrain_splits", "terrain_merges", "terrain_constrained_leaves",
                        "terrain_triangle_budget_hit", "terrain_work_budget_hit", "terrain_seed_triangles",
                        "terrain_seed_interpolated", "terrain_depth_limited_leaves"})
    c.push_back({n, 0});
  c.push_back({"terrain_seed_plants", 1});
  c.push_back({"terrain_achieved_error_px", 3});
  // The terrain rasterised in compute (render/terrain_raster_pass.h); empty otherwise.
  for (const char* n : {"terrain_raster_triangles", "terrain_tile_entries", "terrain_tile_entries_dropped"})
    c.push_back({n, 0});
  for (const char* n : {"plant_seed_triangles", "plant_bins", "plant_clusters", "plant_cluster_slots", "plant_groups",
                        "plants", "plant_overflow", "plant_patches", "plant_triangles"})
    c.push_back({n, 0});
  // Hi-Z occlusion culling of seed triangles (render/hiz_pass.h); empty when it is off.
  for (const char* n : {"plant_cull_tested", "plant_cull_culled", "plant_clusters_culled", "plant_groups_culled",
                        "plants_culled"})
    c.push_back({n, 0});
  // Trees (issue 20, render/tree_layout.h, scene/tree_field.h); empty without trees. Per level the
  // trees appended to its draws (a tree cross-fading between two counts in both).
  for (const char* n : {"trees_full", "trees_reduced", "trees_impostor", "trees_dropped", "trees_classified",
                        "tree_tiles_wanted", "tree_tiles_drawn", "tree_pages_used", "tree_page_capacity",
                        "tree_budget_bound", "tree_gpu_bytes"})
    c.push_back({n, 0});
  c.push_back({"tree_placement_ms", 4});
}

}  // namespace

std::vector<RecordColumn> frameColumns(const std::vector<std::string>& gpuPasses) {
  std::vector<RecordColumn> c = {{"frame", 0},
                                 {"t_s", 6},
                                 {"lat", 9},
                                 {"lon", 9},
                                 {"alt_msl_m", 3},
                                 {"height_above_ground_m", 3},
                                 {"heading_deg", 4},
                                 {"pitch_deg", 4},
                                 {"cpu_flight_ms", 6},
                                 {"cpu_streaming_ms", 6},
                                 {"cpu_terrain_ms", 6},
                                 {"cpu_seeding_ms", 6},
                                 {"cpu_simulation_ms", 6},
                                 {"cpu_record_submit_ms", 6},
                                 {"cpu_frame_ms", 6},
                                 {"gpu_frame_ms", 4}};
  for (const auto& p : gpuPasses) c.push_back({gpuPassColumn(p), 4});
  c.push_back({"wall_ms", 4});
  c.push_back({"recorder_ms", 6});  // sub-microsecond: nanosecond digits
  c.push_back({"png_ms", 4});
  addStreamingColumns(c);
  addTerrainAndPlantColumns(c);
  // The sun (issue 39, scene/sun_clock.h): seen from the dataset's centre at the frame's date-time.
  c.push_back({"sun_azimuth_deg", 4});
  c.push_back({"sun_elevation_deg", 4});
  return c;
}

}  // namespace vegstream::flight
