#pragma once
// The one shared simulation's place in the frame (DESIGN.md "Data flow of one frame"): the
// frame driver (scene/frame_driver.h) steps it once per frame, between preparing the frame and
// submitting it, with the frame's flight time. Wind, the interaction field and tree bending
// arrive with their own issue (19); until then a step does nothing and says so: simulates()
// is false, and the recordings leave cpu_simulation_ms empty rather than writing 0.

namespace vegstream::simulation {

struct StepInput {
  double timeS = 0.0;  // flight (or session) time of the frame
  double dtS = 0.0;    // since the previous step; 0 for the first
};

class Simulation {
 public:
  // Advances the shared state to input.timeS. Nothing is simulated yet.
  void step(const StepInput& input) { lastTimeS_ = input.timeS; }
  // Whether a step does any work (false until the wind field lands): the frame record's
  // simulation time is left empty while it is false.
  bool simulates() const { return false; }
  double lastTimeS() const { return lastTimeS_; }

 private:
  double lastTimeS_ = 0.0;
};

}  // namespace vegstream::simulation
