// Frame records → frames.csv rows (frame_table.h). The order of the cells is the order of
// flight::frameColumns; the asserts keep the two in step.

#include "scene/frame_table.h"

#include <cassert>

#include "flight/frame_columns.h"

namespace vegstream::scene {
namespace {

using flight::kNoValue;

double count(uint64_t v) { return static_cast<double>(v); }

double passMs(const render::GpuTimings& gpu, std::size_t p, const std::string& pass) {
  return p < gpu.passes.size() && gpu.passes[p].pass == pass ? gpu.passes[p].ms : kNoValue;
}

// One row's cells, written in the order of flight::frameColumns.
using Row = std::vector<double>;

// The frame, its time and pose, and the CPU stages' and the GPU frame's times.
void putPoseAndTimes(Row& r, std::size_t& c, std::size_t i, const FrameRecord& f) {
  const SceneFrameFigures& fig = f.scene;
  r[c++] = static_cast<double>(i);
  r[c++] = f.timeS;
  r[c++] = f.pose.position.latDeg;
  r[c++] = f.pose.position.lonDeg;
  r[c++] = f.pose.position.heightM;
  r[c++] = f.pose.heightAboveGroundM;
  r[c++] = f.pose.headingDeg;
  r[c++] = f.pose.pitchDeg;
  r[c++] = f.flightMs;
  r[c++] = fig.streamingMs;
  r[c++] = fig.terrainMs;
  r[c++] = fig.seedingMs;   // the seed triangles made ready for the classify pass (binning: in record/submit)
  r[c++] = f.simulationMs;  // NaN (empty) while the simulation does nothing
  r[c++] = f.recordSubmitMs;
  r[c++] = f.cpuMs();
  r[c++] = f.gpu.frameMs;
}

// The terrain's triangles and the pipeline statistics.
void putGpuCounts(Row& r, std::size_t& c, const FrameRecord& f) {
  r[c++] = count(f.terrainTriangles);
  const render::PipelineStatistics& stats = f.gpu.statistics;
  r[c++] = stats.available ? count(stats.inputPrimitives) : kNoValue;
  r[c++] = stats.available ? count(stats.clippingPrimitives) : kNoValue;
  r[c++] = stats.available ? count(stats.fragmentInvocations) : kNoValue;
}

// Memory, streaming and the terrain's pieces.
void putStreaming(Row& r, std::size_t& c, const SceneFrameFigures& fig) {
  r[c++] = count(fig.cpuBytes);
  r[c++] = count(fig.gpuBytes);
  const streaming::StreamingFrameStats& st = fig.streaming;
  const terrain::TerrainFrameFigures& tf = fig.terrain;
  r[c++] = fig.settleWaitMs;
  r[c++] = st.longestWaitS * 1000.0;
  for (uint64_t v : {st.requestsIssued,
                     st.requestsCompleted,
                     st.requestsCancelled,
                     st.requestsFailed,
                     st.requestsMissing,
                     st.retries,
                     st.bytesRead,
                     fig.uploads,
                     st.uploadBytes,
                     st.evictionsCpu,
                     st.evictionsGpu,
                     st.tilesResidentCpu,
                     st.tilesResidentGpu,
                     st.bytesResidentCpu,
                     st.bytesResidentGpu,
                     st.requestsInFlight,
                     st.wanted,
                     st.wantedResident,
                     tf.lookAheadWants,
                     tf.pieces,
                     tf.fallbackPieces,
                     static_cast<uint64_t>(tf.maxLevelsCoarser),
                     tf.meshesBuilt})
    r[c++] = count(v);
  r[c++] = tf.errorBoundPx;
  r[c++] = tf.relaxation;
}

// ROAM and the seed triangles, and the compute raster's counts.
void putRoam(Row& r, std::size_t& c, const FrameRecord& f) {
  const terrain::TerrainFrameFigures& tf = f.scene.terrain;
  // ROAM and seed triangles (sub-stages of cpu_terrain_ms, not added to cpu_frame_ms).
  r[c++] = tf.roam.updateMs;
  r[c++] = tf.roam.outputMs;
  r[c++] = tf.roam.compactWaitMs;
  r[c++] = tf.roam.prioritiesMs;
  r[c++] = tf.roam.splitMs;
  for (uint64_t v : {tf.roam.leaves, tf.roam.splits, tf.roam.merges, tf.roam.constrainedLeaves,
                     static_cast<uint64_t>(tf.roam.budgetLimited), static_cast<uint64_t>(tf.roam.workLimited),
                     tf.roam.seedTriangles, tf.roam.seedInterpolated, tf.roam.depthLimitedLeaves})
    r[c++] = count(v);
  r[c++] = tf.roam.seedPlants;
  r[c++] = tf.roam.achievedErrorPx;
  for (uint64_t x : {f.terrainRasterTriangles, f.terrainTileEntries, f.terrainTileEntriesDropped})
    r[c++] = f.terrainRasterised ? count(x) : kNoValue;
}

// The classify pass, the plants' statistics and the Hi-Z culling.
void putPlants(Row& r, std::size_t& c, const FrameRecord& f) {
  const render::PipelineStatistics& stats = f.gpu.statistics;
  // The classify pass (render/classify_pass.h); empty when plants are off.
  const auto& v = f.vegetation;
  for (uint64_t x :
       {uint64_t{v ? v->seedTriangles : 0u}, uint64_t{v ? v->bins : 0u}, v ? v->clusters : 0, v ? v->clusterSlots : 0,
        v ? v->groupsTotal : 0, v ? v->plantsTotal : 0, uint64_t{v && v->overflow}})
    r[c++] = v ? count(x) : kNoValue;
  // Only the plant pipelines tessellate and run geometry shaders: their statistics are these.
  r[c++] = v && stats.available ? count(stats.tessControlPatches) : kNoValue;
  // The compute blade path counts its triangles itself (no geometry stage runs).
  r[c++] = v && v->bladeCounts    ? count(v->bladeTriangles)
           : v && stats.available ? count(stats.geometryPrimitives)
                                  : kNoValue;
  // Hi-Z occlusion culling; empty when it did not run (off, or no plants).
  const bool culled = v && v->occlusionCulling;
  for (uint64_t x : {culled ? v->cullTested : 0, culled ? v->cullCulled : 0, culled ? v->cullClustersCulled : 0,
                     culled ? v->cullGroupsCulled : 0,
                     culled ? v->cullPlantsCulled + v->cullGroupPlantsCulled : 0})
    r[c++] = culled ? count(x) : kNoValue;
}

// The trees and the sun.
void putTreesAndSun(Row& r, std::size_t& c, const FrameRecord& f) {
  const SceneFrameFigures& fig = f.scene;
  const auto& t = f.trees;
  for (uint64_t x : {uint64_t{t ? t->full : 0u}, uint64_t{t ? t->reduced : 0u}, uint64_t{t ? t->impostor : 0u},
                     uint64_t{t ? t->dropped : 0u}, uint64_t{t ? t->instances : 0u}})
    r[c++] = t ? count(x) : kNoValue;
  for (uint64_t x : {uint64_t{fig.treeTilesWanted}, uint64_t{fig.treeTilesDrawn}, uint64_t{fig.treePagesUsed},
                     uint64_t{fig.treePageCapacity}, uint64_t{fig.treeBudgetBound}, fig.treeGpuBytes})
    r[c++] = fig.trees ? count(x) : kNoValue;
  r[c++] = fig.trees ? fig.treePlacementMs : kNoValue;
  r[c++] = f.sun.azimuthDeg;
  r[c++] = f.sun.elevationDeg;
}

}  // namespace

flight::RecordTable frameTable(const std::vector<FrameRecord>& records, const std::vector<double>& wallMs,
                               const std::vector<double>& recorderMs, const std::vector<double>& pngMs,
                               const FrameTableLayout& layout) {
  assert(wallMs.size() == records.size() && recorderMs.size() == records.size() && pngMs.size() == records.size());
  flight::RecordTable table(flight::frameColumns(layout.gpuPasses));
  [[maybe_unused]] const std::size_t passColumn0 = *table.find("gpu_frame_ms") + 1;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const FrameRecord& f = records[i];
    auto& r = table.addRow();
    std::size_t c = 0;
    putPoseAndTimes(r, c, i, f);
    assert(c == passColumn0);
    for (std::size_t p = 0; p < layout.gpuPasses.size(); ++p)
      r[c++] = layout.perPassMeaningful ? passMs(f.gpu, p, layout.gpuPasses[p]) : kNoValue;
    r[c++] = wallMs[i];
    r[c++] = recorderMs[i];
    r[c++] = pngMs[i];
    putGpuCounts(r, c, f);
    putStreaming(r, c, f.scene);
    putRoam(r, c, f);
    putPlants(r, c, f);
    putTreesAndSun(r, c, f);
    assert(c == r.size());
  }
  return table;
}

}  // namespace vegstream::scene
