#include "app/simulation_cli.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "core/number_text.h"

namespace vegstream::app {
namespace {

constexpr double kMaxTrailBudgetMb = 1e6;  // as --cpu-budget-mb / --gpu-budget-mb

}  // namespace

void addSimulationOptions(CLI::App& cmd, SimulationCli& out) {
  const simulation::SimulationOptions defaults;
  cmd.add_option("--wind-speed", out.windSpeedMps,
                 "Mean wind 10 m above the ground, m/s, 0 … 100 (default: the flight path's wind section, else " +
                     numberText(defaults.wind.speedMps) + ")");
  cmd.add_option("--wind-direction", out.windDirectionDeg,
                 "Where the wind comes FROM, degrees clockwise from north (270: a west wind) (default: the flight "
                 "path's wind section, else " +
                     numberText(defaults.wind.directionDeg) + ")");
  cmd.add_option("--gustiness", out.gustiness,
                 "Turbulence and gusts relative to the mean wind, 0 (steady) … 1 (default: the flight path's wind "
                 "section, else " +
                     numberText(defaults.wind.gustiness) + ")");
  cmd.add_option("--trail-budget-mb", out.trailBudgetMb,
                 "GPU memory of the trail store (plants pushed down by colliders), MiB, more than 0 (default " +
                     numberText(simulation::kDefaultTrailBudgetMb) + ")");
}

Status checkSimulationOptions(const SimulationCli& o) {
  auto bad = [](const std::string& m) { return makeError(ErrorKind::InvalidInput, m); };
  if (o.windSpeedMps && !(*o.windSpeedMps >= 0.0 && *o.windSpeedMps <= simulation::kMaxWindSpeedMps))
    return bad("--wind-speed " + numberText(*o.windSpeedMps) + ": must be 0 … " + numberText(simulation::kMaxWindSpeedMps) +
               " m/s");
  if (o.windDirectionDeg && !std::isfinite(*o.windDirectionDeg))
    return bad("--wind-direction " + numberText(*o.windDirectionDeg) +
               ": must be a finite number of degrees (where the wind comes from, clockwise from north)");
  if (o.gustiness && !(*o.gustiness >= 0.0 && *o.gustiness <= 1.0))
    return bad("--gustiness " + numberText(*o.gustiness) + ": must be 0 … 1");
  if (o.trailBudgetMb && !(*o.trailBudgetMb > 0.0 && *o.trailBudgetMb <= kMaxTrailBudgetMb))
    return bad("--trail-budget-mb " + numberText(*o.trailBudgetMb) + ": must be more than 0 and at most 1000000 MiB");
  return {};
}

simulation::SimulationOptions resolveSimulationOptions(const SimulationCli& cli, const flight::FlightPath* path) {
  simulation::SimulationOptions out;
  simulation::WindOptions& wind = out.wind;
  if (path != nullptr && path->wind) {
    const flight::WindSection& w = *path->wind;
    wind.speedMps = w.speedMps.value_or(wind.speedMps);
    wind.directionDeg = w.directionDeg.value_or(wind.directionDeg);
    wind.gustiness = w.gustiness.value_or(wind.gustiness);
  }
  wind.speedMps = cli.windSpeedMps.value_or(wind.speedMps);
  wind.directionDeg = cli.windDirectionDeg.value_or(wind.directionDeg);
  wind.gustiness = cli.gustiness.value_or(wind.gustiness);
  out.trailBudgetMb = cli.trailBudgetMb.value_or(out.trailBudgetMb);
  return out;
}

}  // namespace vegstream::app
