// The trees stage's figures (frame_figures.h): the tree field's tiles and pages
// (TreeFieldFigures) and the renderer's tree pool; empty without trees. What the tree pass drew is
// the render stage's.

#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

void declareTreeFigures(FrameFigures& out, const FigureLayout&) {
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
}

}  // namespace vegstream::scene
