// The simulation stage's figures (frame_figures.h): its CPU step (the GPU's is the render
// stage's gpu_simulation_ms).

#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

void declareSimulationFigures(FrameFigures& out, const FigureLayout&) {
  // NaN (empty) while the simulation does nothing.
  out.push_back(
      {FigureSection::CpuStages, {"cpu_simulation_ms", 6, "ms"}, [](const FrameRecord& r) { return r.simulationMs; }});
}

}  // namespace vegstream::scene
