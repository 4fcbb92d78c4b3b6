#pragma once
// One stage of the frame: streaming, terrain, seeding, trees (the scene's, scene.h), simulation
// and render (the driver's, frame_driver.h), run in that order over one FrameContext. Each stage
// does its part in run() — reads the context's views and what the stages before it handed on,
// adds its own — and declares its per-frame figures (frame_figure.h) in a static
// `declareFigures(FrameFigures&, const FigureLayout&)` in its own file, which frame_figures.h lists.
//
// Contract: run() is called once per frame, in the list's order; a stage keeps what the request
// points at alive until its next run().

#include "scene/frame_context.h"

namespace vegstream::scene {

class FrameStage {
 public:
  virtual ~FrameStage() = default;
  virtual void run(FrameContext& context) = 0;
};

}  // namespace vegstream::scene
