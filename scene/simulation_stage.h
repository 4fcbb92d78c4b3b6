#pragma once
// The simulation stage (frame_stage.h): the shared simulation's step at the frame's time
// (simulation/simulation.h) — the path's colliders and wind sources brought into the local frame
// over the scene's ground, the camera as the frame's — CPU bookkeeping only, producing the
// GpuStep the renderer integrates (FrameRequest::simulation). Figures: cpu_simulation_ms (NaN
// while the simulation does nothing).

#include <optional>
#include <vector>

#include "scene/frame_figure.h"
#include "scene/frame_stage.h"
#include "simulation/simulation.h"

namespace vegstream::scene {

class Scene;

class SimulationStage final : public FrameStage {
 public:
  SimulationStage(const Scene& scene, const simulation::SimulationOptions& options)
      : scene_(scene), simulation_(options) {}
  // Steps with the context's input (FrameContext::input: colliders, wind sources, the
  // simulation's own clock); without one, at the frame's time with neither.
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

  simulation::Simulation& simulation() { return simulation_; }
  const simulation::Simulation& simulation() const { return simulation_; }

 private:
  void bringInputs(const FrameContext& context);

  const Scene& scene_;
  simulation::Simulation simulation_;
  std::optional<double> lastStepS_;
  std::vector<simulation::ColliderState> colliders_;  // the latest step's inputs (local ENU)
  std::vector<simulation::WindSourceState> sources_;
};

}  // namespace vegstream::scene
