// The trees stage (tree_stage.h): its run and its figures — the tree field's tiles and pages
// (TreeFieldFigures) and the renderer's tree pool; empty without trees. What the tree pass drew is
// the render stage's.

#include "scene/tree_stage.h"

#include "scene/frame_driver.h"

namespace vegstream::scene {

void TreeStage::run(FrameContext& context) {
  SceneFrameFigures& fig = context.figures;
  context.request.trees = &field_.prepare(context.camera.position, settled_);
  if (context.request.vegetation) {  // relative to the camera the seed triangles are relative to
    field_.fillCanopy(context.camera.position, canopy_);
    context.vegetation.canopy = &canopy_;
  }
  const TreeFieldFigures& t = field_.figures();
  fig.trees = t;
  // Settled frames wait for their tiles' trees as for their tiles; realtime ones place a few.
  (settled_ ? fig.settleWaitMs : fig.seedingMs) += t.placementMs;
  fig.treeGpuBytes = renderer_.treeGpuBytes();
}

void TreeStage::declareFigures(FrameFigures& out, const FigureLayout&) {
  using R = const FrameRecord&;
  using T = TreeFieldFigures;
  const auto add = [&out](const char* name, const char* unit, int decimals, double (*value)(const T&)) {
    out.push_back({FigureSection::TreeField, {name, decimals, unit}, [value](R r) {
                     return r.scene.trees ? value(*r.scene.trees) : flight::kNoValue;
                   }});
  };
  add("tree_tiles_wanted", "tiles", 0, [](const T& t) { return count(t.tilesWanted); });
  add("tree_tiles_drawn", "tiles", 0, [](const T& t) { return count(t.tilesDrawn); });
  add("tree_pages_used", "pages", 0, [](const T& t) { return count(t.pagesUsed); });
  add("tree_page_capacity", "pages", 0, [](const T& t) { return count(t.pageCapacity); });
  add("tree_budget_bound", "flag", 0, [](const T& t) { return count(t.budgetBound); });
  out.push_back({FigureSection::TreeField, {"tree_gpu_bytes", 0, "bytes"}, [](R r) {
                   return r.scene.trees ? count(r.scene.treeGpuBytes) : flight::kNoValue;
                 }});
  add("tree_placement_ms", "ms", 4, [](const T& t) { return t.placementMs; });
  // The tiles placed this frame: what tree_placement_ms paid for (realtime: at most two a frame).
  add("tree_tiles_placed", "tiles", 0, [](const T& t) { return count(t.placed); });
}

}  // namespace vegstream::scene
