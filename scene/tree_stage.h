#pragma once
// The trees stage (frame_stage.h): the tree field's tiles around the camera placed and paged
// (tree_field.h; settled frames place every wanted tile, realtime ones a few) as the frame's
// tree request, and the crowns the plants thin under when the frame has plants. Present only
// when the scene has trees. Figures: the field's tiles, pages and placement time, the renderer's
// tree pool; the placement counts as settled waiting (settled) or seeding (realtime).

#include "render/renderer.h"
#include "scene/frame_figure.h"
#include "scene/frame_stage.h"
#include "scene/tree_field.h"
#include "vegetation/canopy_cells.h"

namespace vegstream::scene {

class TreeStage final : public FrameStage {
 public:
  TreeStage(TreeField& field, const render::Renderer& renderer, bool settled)
      : field_(field), renderer_(renderer), settled_(settled) {}
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

 private:
  TreeField& field_;
  const render::Renderer& renderer_;
  bool settled_;
  vegetation::CanopyTable canopy_;  // what the plants' request points at
};

}  // namespace vegstream::scene
