#pragma once
// `vegstream inspect TOPIC …`: the CPU reference of one precomputed thing, as JSON on stdout.
// Topics:
//   blade-shape --stiffness K [--segments N] [--root-tilt R]: the static blade shape of core
//     seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.3 eq. 5–12 (vegetation/blade_shape.h):
//     {"stiffness": K, "segments": N, "root_tilt": R, "phi": [N hinge angles, rad, root first,
//      phi[0] includes the root tilt], "inclination": [N segment angles from vertical, rad],
//      "points": [[lateral, height] × (N + 1), root first, unit segments], "residual": max |F_n|,
//      "iterations": Newton iterations, "critical_stiffness": the straight blade's buckling k′}.
//     N defaults to 4 (1 … 16), R to 0.1 rad ([0, π/2)).

#include <string>

#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct InspectOptions {
  std::string topic;      // empty: none given
  std::string stiffness;  // parsed by runInspect, so every bad value is one message naming the option
  std::string segments = "4";
  std::string rootTilt = "0.1";
};

CLI::App* addInspectCommand(CLI::App& cli, InspectOptions& options);

// Exit code: 0 done; 2 no or an unknown topic (the message lists the topics), a missing or bad
// --stiffness / --segments / --root-tilt (one message naming it); 1 the solver did not converge.
int runInspect(const InspectOptions& options, const Logger& log);

}  // namespace vegstream::app
