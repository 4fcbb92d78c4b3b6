// The simulation stage (simulation_stage.h): its run and its figures — its CPU step (the GPU's is
// the render stage's gpu_simulation_ms).

#include "scene/simulation_stage.h"

#include <cmath>

#include "core/stopwatch.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

// The input's colliders and wind sources in the local frame, over the scene's ground.
void SimulationStage::bringInputs(const FrameContext& context) {
  const geo::LocalFrame& frame = scene_.frame();
  // The ground under a point, in the local frame; where the data has none, the point's own height.
  const auto groundZ = [&](const geo::Geodetic& g, double fallbackMsl) {
    const double h = scene_.groundHeight(g.latDeg, g.lonDeg);
    return frame.toLocal({g.latDeg, g.lonDeg, std::isnan(h) ? fallbackMsl : h}).z;
  };
  colliders_.clear();
  sources_.clear();
  if (!context.input) return;
  for (const flight::ColliderSample& c : context.input->colliders) {
    simulation::ColliderState s;
    s.centre = frame.toLocal(c.centre);
    s.radiusM = c.radiusM;
    s.lengthM = c.lengthM;
    s.groundZ = groundZ(c.centre, c.centre.heightM - 0.5 * c.lengthM - c.radiusM);
    colliders_.push_back(s);
  }
  for (const flight::WindSourceSample& w : context.input->windSources) {
    simulation::WindSourceState s;
    s.type = w.type == flight::WindSourceSpec::Type::Fan         ? simulation::WindSourceType::Fan
             : w.type == flight::WindSourceSpec::Type::Whirlwind ? simulation::WindSourceType::Whirlwind
                                                                 : simulation::WindSourceType::Rotor;
    s.position = frame.toLocal(w.centre);
    s.groundZ = groundZ(w.centre, w.centre.heightM);
    s.radiusM = w.radiusM;
    s.strengthMps = w.strengthMps;
    s.directionDeg = w.directionDeg;
    sources_.push_back(s);
  }
}

void SimulationStage::run(FrameContext& context) {
  Stopwatch watch;
  bringInputs(context);
  const double t = context.input && context.input->simulationTimeS ? *context.input->simulationTimeS : context.timeS;
  const double dt = lastStepS_ ? t - *lastStepS_ : 0.0;
  simulation_.step({t, dt, context.camera.position, colliders_, sources_});
  lastStepS_ = t;
  if (!simulation_.simulates()) return;
  context.request.simulation = &simulation_.gpuStep();
  context.simulationMs = watch.elapsedMs();
}

void SimulationStage::declareFigures(FrameFigures& out, const FigureLayout&) {
  // NaN (empty) while the simulation does nothing.
  out.push_back(
      {FigureSection::CpuStages, {"cpu_simulation_ms", 6, "ms"}, [](const FrameRecord& r) { return r.simulationMs; }});
}

}  // namespace vegstream::scene
