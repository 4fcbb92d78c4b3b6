// The render stage (render_stage.h): its run and its figures — recording and submitting, the GPU
// frame and its passes, the pipeline statistics, the GPU memory, the compute raster, the classify
// pass with its culling, and the trees drawn (render::FrameResult, as the driver collected it).

#include "scene/render_stage.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include "flight/frame_columns.h"
#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

namespace {

using S = FigureSection;
using R = const FrameRecord&;
using flight::kNoValue;

// The GPU frame and one column per pass, named by the layout (empty where per-pass times mean
// nothing, or the frame's pass is not the layout's).
void declareGpuTimes(FrameFigures& out, const FigureLayout& layout) {
  out.push_back({S::GpuFrame, {flight::column::kGpuFrameMs, 4, "ms"}, [](R r) { return r.gpu.frameMs; }});
  for (std::size_t p = 0; p < layout.gpuPasses.size(); ++p) {
    FrameFigure f;  // member by member: GCC 12 sees an uninitialised string in the braced form here
    f.section = S::GpuFrame;
    f.column.name = flight::column::gpuPassColumn(layout.gpuPasses[p]);
    f.column.unit = "ms";
    f.value = [p, pass = layout.gpuPasses[p], meaningful = layout.perPassMeaningful](R r) {
      return meaningful && p < r.gpu.passes.size() && r.gpu.passes[p].pass == pass ? r.gpu.passes[p].ms : kNoValue;
    };
    out.push_back(std::move(f));
  }
}

// The terrain pass's triangles and the pipeline statistics over the frame.
void declareGpuCounts(FrameFigures& out) {
  using Stats = render::PipelineStatistics;
  out.push_back({S::GpuCounts, {flight::column::kTerrainTriangles, 0, "triangles"}, [](R r) {
                   return count(r.terrainTriangles);
                 }});
  // The terrain's vertices on the GPU (render/terrain_geometry_buffers.h): chunks drawn, chunks
  // and vertices uploaded (0 with `--terrain-geometry copied`).
  const auto geometry = [&out](const char* name, const char* unit, uint64_t FrameRecord::*field) {
    out.push_back({S::GpuCounts, {name, 0, unit}, [field](R r) { return count(r.*field); }});
  };
  geometry("terrain_chunks", "chunks", &FrameRecord::terrainChunksDrawn);
  geometry("terrain_chunks_uploaded", "chunks", &FrameRecord::terrainChunksUploaded);
  geometry("terrain_vertices_uploaded", "vertices", &FrameRecord::terrainVerticesUploaded);
  const auto stat = [&out](const char* name, uint64_t Stats::*field) {
    out.push_back({S::GpuCounts, {name, 0, "primitives"}, [field](R r) {
                     return r.gpu.statistics.available ? count(r.gpu.statistics.*field) : kNoValue;
                   }});
  };
  stat("stat_input_primitives", &Stats::inputPrimitives);
  stat("stat_clipping_primitives", &Stats::clippingPrimitives);
  stat("stat_fragment_invocations", &Stats::fragmentInvocations);
}

// The terrain rasterised in compute (render/terrain_raster_pass.h); empty otherwise.
void declareComputeRaster(FrameFigures& out) {
  struct Count {
    const char* name;
    const char* unit;
    uint64_t FrameRecord::*field;
  };
  static const Count counts[] = {
      {"terrain_raster_triangles", "triangles", &FrameRecord::terrainRasterTriangles},
      {"terrain_tile_entries", "entries", &FrameRecord::terrainTileEntries},
      {"terrain_tile_entries_dropped", "entries", &FrameRecord::terrainTileEntriesDropped},
      {"terrain_depth_tiles", "tiles", &FrameRecord::terrainDepthTiles},
      {"terrain_depth_edge_tiles", "tiles", &FrameRecord::terrainDepthEdgeTiles},
  };
  for (const Count& c : counts)
    out.push_back({S::Terrain, {c.name, 0, c.unit}, [field = c.field](R r) {
                     return r.terrainRasterised ? count(r.*field) : kNoValue;
                   }});
}

// The classify pass (render/classify_pass.h) and the plants' statistics; empty when plants are off.
void declarePlantFigures(FrameFigures& out) {
  using V = render::VegetationFigures;
  const auto add = [&out](const char* name, const char* unit, double (*value)(const V&)) {
    out.push_back(
        {S::Plants, {name, 0, unit}, [value](R r) { return r.vegetation ? value(*r.vegetation) : kNoValue; }});
  };
  add("plant_seed_triangles", "triangles", [](const V& v) { return count(v.seedTriangles); });
  add("plant_bins", "bins", [](const V& v) { return count(v.bins); });
  add("plant_clusters", "clusters", [](const V& v) { return count(v.clusters); });
  add("plant_cluster_slots", "threads", [](const V& v) { return count(v.clusterSlots); });
  add("plant_groups", "groups", [](const V& v) { return count(v.groupsTotal); });
  add("plants", "plants", [](const V& v) { return count(v.plantsTotal); });
  add("plant_overflow", "flag", [](const V& v) { return count(v.overflow); });
  // Only the plant pipelines tessellate and run geometry shaders: their statistics are these.
  out.push_back({S::Plants, {"plant_patches", 0, "patches"}, [](R r) {
                   return r.vegetation && r.gpu.statistics.available ? count(r.gpu.statistics.tessControlPatches)
                                                                     : kNoValue;
                 }});
  // The compute blade path counts its triangles itself (no geometry stage runs).
  out.push_back({S::Plants, {"plant_triangles", 0, "triangles"}, [](R r) {
                   return r.vegetation && r.vegetation->bladeCounts    ? count(r.vegetation->bladeTriangles)
                          : r.vegetation && r.gpu.statistics.available ? count(r.gpu.statistics.geometryPrimitives)
                                                                       : kNoValue;
                 }});
  // Hi-Z occlusion culling (render/hiz_pass.h); empty when it did not run (off, or no plants).
  const auto culled = [&out](const char* name, const char* unit, double (*value)(const V&)) {
    out.push_back({S::Plants, {name, 0, unit}, [value](R r) {
                     return r.vegetation && r.vegetation->occlusionCulling ? value(*r.vegetation) : kNoValue;
                   }});
  };
  culled("plant_cull_tested", "triangles", [](const V& v) { return count(v.cullTested); });
  culled("plant_cull_culled", "triangles", [](const V& v) { return count(v.cullCulled); });
  culled("plant_clusters_culled", "clusters", [](const V& v) { return count(v.cullClustersCulled); });
  culled("plant_groups_culled", "groups", [](const V& v) { return count(v.cullGroupsCulled); });
  culled("plants_culled", "plants", [](const V& v) { return count(v.cullPlantsCulled + v.cullGroupPlantsCulled); });
}

// The trees the tree pass appended per level (a tree cross-fading between two counts in both)
// and classified (issue 20, render/tree_layout.h); empty without trees.
void declareTreeDrawFigures(FrameFigures& out) {
  using T = render::TreeFigures;
  const auto add = [&out](const char* name, double (*value)(const T&)) {
    out.push_back({S::TreeDraws, {name, 0, "trees"}, [value](R r) { return r.trees ? value(*r.trees) : kNoValue; }});
  };
  add("trees_full", [](const T& t) { return count(t.full); });
  add("trees_reduced", [](const T& t) { return count(t.reduced); });
  add("trees_impostor", [](const T& t) { return count(t.impostor); });
  add("trees_dropped", [](const T& t) { return count(t.dropped); });
  add("trees_classified", [](const T& t) { return count(t.instances); });
}

}  // namespace

void RenderStage::run(FrameContext& context) {
  render::FrameRequest& request = context.request;
  if (const FrameInput* input = context.input) {
    if (input->sunTimeS) request.lighting = scene_.lightingAt(*input->sunTimeS);
    request.lighting.adaptExposure = input->adaptExposure;
    // The window's exposure moves with the time between its frames (the first frame: none).
    if (input->adaptExposure && lastTimeS_)
      request.lighting.adaptSeconds = float(std::clamp(input->timeS - *lastTimeS_, 0.0, 1.0));
    lastTimeS_ = input->timeS;
    request.present = input->present;
    request.readbackColor = input->readbackColor;
    request.aov = input->aov;
    request.overlay = input->overlay;
  }
  context.figures.gpuBytes = scene_.renderer().gpuBytes();
  context.submitted = scene_.renderer().submitFrame(request);
}

void RenderStage::declareFigures(FrameFigures& out, const FigureLayout& layout) {
  out.push_back({S::CpuStages, {"cpu_record_submit_ms", 6, "ms"}, [](R r) { return r.recordSubmitMs; }});
  declareGpuTimes(out, layout);
  declareGpuCounts(out);
  out.push_back({S::Memory, {flight::column::kGpuBytes, 0, "bytes"}, [](R r) { return count(r.scene.gpuBytes); }});
  declareComputeRaster(out);
  declarePlantFigures(out);
  declareTreeDrawFigures(out);
}

}  // namespace vegstream::scene
