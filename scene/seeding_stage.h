#pragma once
// The seeding stage (frame_stage.h): the terrain's fixed-level seed triangles made ready for the
// classify pass — camera-relative, with their keys and imagery (seedTrianglesForGpu, scene.h) —
// as the frame's plant request (FrameContext::vegetation, FrameRequest::vegetation); nothing
// without plants. Figures: cpu_seeding_ms (the binning is in cpu_record_submit_ms; what the pass
// made of them is the render stage's).

#include <vector>

#include "render/frame_types.h"
#include "scene/frame_figure.h"
#include "scene/frame_stage.h"
#include "scene/scene.h"

namespace vegstream::scene {

class SeedingStage final : public FrameStage {
 public:
  SeedingStage(terrain::StreamedTerrain& terrain, const SceneOptions& options) : terrain_(terrain), options_(options) {}
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

 private:
  terrain::StreamedTerrain& terrain_;
  const SceneOptions& options_;
  std::vector<render::SeedTriangleGpu> seeds_;  // what the request points at
};

}  // namespace vegstream::scene
