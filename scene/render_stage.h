#pragma once
// The render stage (frame_stage.h), the last: the request the stages before it filled, with what
// the driver's input asks of the frame — the sun at the input's own clock, the window's exposure
// adaptation, presenting, read-backs, the overlay — recorded and submitted by the renderer
// (FrameContext::submitted: the frame's index or the error). Its figures come back when the
// driver collects the frame (render::FrameResult in the record): record/submit time, the GPU
// frame and passes, pipeline statistics, GPU memory, the compute raster, the classify pass, the
// trees drawn.

#include <optional>

#include "scene/frame_figure.h"
#include "scene/frame_stage.h"

namespace vegstream::scene {

class Scene;

class RenderStage final : public FrameStage {
 public:
  explicit RenderStage(Scene& scene) : scene_(scene) {}
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

 private:
  Scene& scene_;
  std::optional<double> lastTimeS_;  // the last submitted frame's time (the window's exposure adaptation)
};

}  // namespace vegstream::scene
