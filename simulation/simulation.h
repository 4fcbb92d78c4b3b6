#pragma once
// The one shared simulation (issue 19; DESIGN.md "Data flow of one frame"): the frame driver
// (scene/frame_driver.h) steps it once per frame, between preparing the frame and submitting it,
// with the frame's flight time, the camera, the colliders and the wind sources of that instant.
//
// A step is CPU bookkeeping only — the fixed sub-step clock, the world-aligned windows of the wind
// grid and of the interaction field, the trail store's transfers (interaction_window.h), the
// colliders and sources made camera-relative — and its result is one GpuStep: the simulation block
// (simulation/shared/simulation_layout.glsl) and the transfers that render/simulation_pass.h
// records. The GPU integrates the virtual blades and updates the interaction field; the plants
// read both. simulation/shared_code.h runs the same shader code on the CPU as the reference.
//
// Determinism: the sub-step clock counts whole kSubstepS from time 0 (a frame at time t has run
// floor(t / kSubstepS) of them, at most kMaxSubsteps per frame), so the same flight times give
// the same steps whatever the frame rate's jitter on the CPU. Time going backwards (a new flight
// in the same session) restarts everything: every virtual blade starts at rest again, the
// interaction field and the trail store are emptied.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "simulation/interaction_window.h"
#include "simulation/shared_code.h"
#include "simulation/simulation_options.h"

namespace vegstream::simulation {

struct StepInput {
  double timeS = 0.0;      // flight (or session) time of the frame
  double dtS = 0.0;        // since the previous step; 0 for the first
  glm::dvec3 camera{0.0};  // the scene's local ENU frame (m)
  std::span<const ColliderState> colliders;  // at most kMaxColliders are simulated (the first ones)
  std::span<const WindSourceState> sources;  // at most kMaxWindSources
};

// What the GPU does for one step (render/simulation_pass.h).
struct GpuStep {
  shader::SimulationParams params{};
  std::vector<TileTransfer> transfers;  // Saves first, then Restores and Clears
  bool runWind = false;                 // integrate the wind grid
  bool runInteraction = false;          // update the interaction field
  bool restarted = false;               // the simulation (re)started: the GPU state starts over
};

// The strength (cs) a collider of radius r leaves where it presses the grass fully down: a
// bigger body presses longer (it recovers over strength / kRecoveryPerS seconds).
double colliderStrength(double radiusM);

class Simulation {
 public:
  explicit Simulation(const SimulationOptions& options = {});

  // Advances the shared state to input.timeS (see above).
  void step(const StepInput& input);
  // Whether a step does any work: false only with SimulationOptions::enabled off, and then the
  // recordings leave cpu_simulation_ms empty.
  bool simulates() const { return options_.enabled; }
  double lastTimeS() const { return lastTimeS_; }
  const SimulationOptions& options() const { return options_; }
  // Changes the wind from the next step on (the window's HUD); nothing else restarts.
  void setWind(const WindOptions& wind) { options_.wind = wind; }
  // The latest step's GPU work (meaningful after a step).
  const GpuStep& gpuStep() const { return gpu_; }
  // Sub-steps run so far, and in the latest step.
  int64_t substeps() const { return substepsDone_; }
  const InteractionWindow& interactionWindow() const { return *window_; }

 private:
  void restart(double timeS);
  // step()'s parts, into `p`: the clock (returns the sub-steps this frame runs); the wind and
  // interaction windows around the camera; the colliders, marking the tiles they press (returns
  // how many are simulated).
  int64_t advanceClock(double timeS, shader::SimulationParams& p);
  void placeWindows(const glm::dvec3& cam, double timeS, int64_t steps, shader::SimulationParams& p);
  std::size_t writeColliders(const StepInput& in, shader::SimulationParams& p);

  SimulationOptions options_;
  GpuStep gpu_;
  std::unique_ptr<InteractionWindow> window_;
  int64_t substepsDone_ = 0;
  int32_t generation_ = 0;
  double lastTimeS_ = 0.0;
  bool started_ = false;
  double trailsUntilS_ = -1.0;  // the latest time any texel can still hold a trail
  std::vector<glm::dvec3> previousColliders_;
};

}  // namespace vegstream::simulation
