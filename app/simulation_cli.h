#pragma once
// The simulation options that `fly`, `record` and `snapshot` share (issue 19): --wind-speed,
// --wind-direction, --gustiness, --trail-budget-mb. One definition, so the commands spell and
// check them alike, and one rule for where a value comes from: the command line wins over the
// flight path's "wind" section (flight/flight_path.h), which wins over the defaults of
// simulation/simulation_options.h.

#include <optional>

#include "core/result.h"
#include "flight/flight_path.h"
#include "simulation/simulation_options.h"

namespace CLI {
class App;
}

namespace vegstream::app {

// What the command line gave; an absent value was not given.
struct SimulationCli {
  std::optional<double> windSpeedMps;      // --wind-speed M/S, 0 … 100
  std::optional<double> windDirectionDeg;  // --wind-direction DEG: where the wind comes FROM, clockwise from north
  std::optional<double> gustiness;         // --gustiness 0 … 1
  std::optional<double> trailBudgetMb;     // --trail-budget-mb MB, > 0 (default simulation::kDefaultTrailBudgetMb)
};

// Adds the four options to a subcommand.
void addSimulationOptions(CLI::App& cmd, SimulationCli& out);

// Checks the given values: InvalidInput, one message naming the option and the problem
// ("--wind-speed 101: must be 0 … 100 m/s"), as applyStreamingOptions does for its options.
Status checkSimulationOptions(const SimulationCli& cli);

// The options the simulation runs with: each value from the command line when given, else from
// the path's wind section (path may be null: no path, as for `snapshot`), else the default.
// The values are taken as they are: check them first (checkSimulationOptions; a parsed path is
// already checked).
simulation::SimulationOptions resolveSimulationOptions(const SimulationCli& cli, const flight::FlightPath* path);

}  // namespace vegstream::app
