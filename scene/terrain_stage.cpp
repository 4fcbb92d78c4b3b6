// The terrain stage (terrain_stage.h): its run and its figures — its CPU time, the wants and
// pieces of the streamed terrain, and ROAM with the seed triangles (terrain::TerrainFrameFigures).

#include "scene/terrain_stage.h"

#include "core/stopwatch.h"
#include "flight/frame_columns.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

void TerrainStage::run(FrameContext& context) {
  if (context.repeatsLastFrame()) {
    // The same pieces, still valid (ROAM made no output since), and no update that would change
    // what the next frame draws.
    context.figures.terrain = terrain_.figures();
    context.request.terrain = draws_;
    return;
  }
  Stopwatch stage;
  const std::span<const terrain::TerrainPiece> pieces = terrain_.pieces(context.timeS);
  draws_.clear();
  for (const terrain::TerrainPiece& p : pieces)
    draws_.push_back({p.mesh, p.imageryLayer, p.imageryUv, p.previousLayer, p.previousUv, p.imageryBlend});
  context.figures.terrainMs += stage.elapsedMs();
  context.figures.terrain = terrain_.figures();
  context.request.terrain = draws_;
}

namespace {

// ROAM's own figures (sub-stages of cpu_terrain_ms, not added to cpu_frame_ms).
void declareRoamFigures(FrameFigures& out) {
  using S = FigureSection;
  using R = const FrameRecord&;
  using Roam = terrain::RoamFigures;
  const auto ms = [&out](const char* name, double Roam::*field) {
    out.push_back({S::Terrain, {name, 6, "ms"}, [field](R r) { return r.scene.terrain.roam.*field; }});
  };
  const auto counter = [&out](const char* name, const char* unit, uint64_t Roam::*field) {
    out.push_back({S::Terrain, {name, 0, unit}, [field](R r) { return count(r.scene.terrain.roam.*field); }});
  };
  ms("terrain_roam_update_ms", &Roam::updateMs);
  ms("terrain_roam_output_ms", &Roam::outputMs);
  ms("terrain_roam_compact_wait_ms", &Roam::compactWaitMs);
  ms("terrain_roam_priorities_ms", &Roam::prioritiesMs);
  ms("terrain_roam_split_ms", &Roam::splitMs);
  counter("terrain_leaves", "triangles", &Roam::leaves);
  counter("terrain_splits", "splits", &Roam::splits);
  counter("terrain_merges", "merges", &Roam::merges);
  counter("terrain_constrained_leaves", "triangles", &Roam::constrainedLeaves);
  out.push_back({S::Terrain, {"terrain_triangle_budget_hit", 0, "flag"}, [](R r) {
                   return count(r.scene.terrain.roam.budgetLimited);
                 }});
  out.push_back({S::Terrain, {"terrain_work_budget_hit", 0, "flag"}, [](R r) {
                   return count(r.scene.terrain.roam.workLimited);
                 }});
  counter("terrain_seed_triangles", "triangles", &Roam::seedTriangles);
  counter("terrain_seed_interpolated", "triangles", &Roam::seedInterpolated);
  counter("terrain_depth_limited_leaves", "triangles", &Roam::depthLimitedLeaves);
  out.push_back(
      {S::Terrain, {"terrain_seed_plants", 1, "plants"}, [](R r) { return r.scene.terrain.roam.seedPlants; }});
  out.push_back(
      {S::Terrain, {"terrain_achieved_error_px", 3, "px"}, [](R r) { return r.scene.terrain.roam.achievedErrorPx; }});
}

}  // namespace

void TerrainStage::declareFigures(FrameFigures& out, const FigureLayout&) {
  using S = FigureSection;
  using R = const FrameRecord&;
  namespace col = flight::column;
  out.push_back({S::CpuStages, {"cpu_terrain_ms", 6, "ms"}, [](R r) { return r.scene.terrainMs; }});
  out.push_back({S::Streaming, {"stream_lookahead_wants", 0, "tiles"}, [](R r) {
                   return count(r.scene.terrain.lookAheadWants);
                 }});
  out.push_back({S::Streaming, {"terrain_pieces", 0, "pieces"}, [](R r) { return count(r.scene.terrain.pieces); }});
  out.push_back(
      {S::Streaming, {col::kFallbackPieces, 0, "pieces"}, [](R r) { return count(r.scene.terrain.fallbackPieces); }});
  out.push_back({S::Streaming, {col::kMaxLevelsCoarser, 0, "levels"}, [](R r) {
                   return count(static_cast<uint64_t>(r.scene.terrain.maxLevelsCoarser));
                 }});
  out.push_back(
      {S::Streaming, {"terrain_meshes_built", 0, "meshes"}, [](R r) { return count(r.scene.terrain.meshesBuilt); }});
  out.push_back({S::Terrain, {"terrain_error_bound_px", 3, "px"}, [](R r) { return r.scene.terrain.errorBoundPx; }});
  out.push_back({S::Terrain, {col::kErrorRelaxation, 3, "factor"}, [](R r) { return r.scene.terrain.relaxation; }});
  declareRoamFigures(out);
}

}  // namespace vegstream::scene
