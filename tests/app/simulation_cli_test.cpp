// The simulation options of `fly`, `record` and `snapshot` (app/simulation_cli.h): what the
// command line gave is remembered, checked with one message naming the option, and wins over a
// flight path's wind section, which wins over simulation/simulation_options.h's defaults.

#include <algorithm>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "app/simulation_cli.h"
#include "flight/flight_path_json.h"

namespace vegstream::app {
namespace {

// A path whose wind section gives every value.
flight::FlightPath windyPath() {
  auto p = flight::parseFlightPath(R"({
    "keyframes": [{"t": 0, "lat": 37.2, "lon": -112.98, "alt_m": 500, "heading": 0, "pitch": -10},
                  {"t": 5, "lat": 37.21, "lon": -112.97, "alt_m": 500, "heading": 0, "pitch": -10}],
    "wind": {"speed_mps": 6, "direction_deg": 250, "gustiness": 0.6}
  })",
                                   "windy.json");
  EXPECT_TRUE(p.ok()) << p.error().message;
  return *p;
}

// Parses `args` (after the subcommand's name) with the options added to a subcommand.
SimulationCli parsed(const std::vector<std::string>& args) {
  CLI::App app;
  SimulationCli cli;
  auto* cmd = app.add_subcommand("record");
  addSimulationOptions(*cmd, cli);
  std::vector<std::string> argv = {"record"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::reverse(argv.begin(), argv.end());  // CLI11 takes the arguments reversed
  app.parse(argv);
  return cli;
}

TEST(SimulationCli, RemembersWhichOptionsWereGiven) {
  const SimulationCli none = parsed({});
  EXPECT_FALSE(none.windSpeedMps || none.windDirectionDeg || none.gustiness || none.trailBudgetMb);
  const SimulationCli some = parsed({"--wind-speed", "12.5", "--trail-budget-mb", "32"});
  EXPECT_EQ(some.windSpeedMps, 12.5);
  EXPECT_EQ(some.trailBudgetMb, 32.0);
  EXPECT_FALSE(some.windDirectionDeg.has_value());
  EXPECT_FALSE(some.gustiness.has_value());
  const SimulationCli all = parsed({"--wind-direction", "-90", "--gustiness", "0"});
  EXPECT_EQ(all.windDirectionDeg, -90.0);
  EXPECT_EQ(all.gustiness, 0.0) << "0 given is not 0 absent";
}

TEST(SimulationCli, DefaultsWithoutPathOrOptions) {
  const simulation::SimulationOptions d = resolveSimulationOptions({}, nullptr);
  const simulation::SimulationOptions expected;
  EXPECT_EQ(d.wind.speedMps, expected.wind.speedMps);
  EXPECT_EQ(d.wind.directionDeg, expected.wind.directionDeg);
  EXPECT_EQ(d.wind.gustiness, expected.wind.gustiness);
  EXPECT_EQ(d.trailBudgetMb, simulation::kDefaultTrailBudgetMb);
  EXPECT_TRUE(d.enabled);
  flight::FlightPath noWind = windyPath();
  noWind.wind.reset();
  EXPECT_EQ(resolveSimulationOptions({}, &noWind).wind.gustiness, expected.wind.gustiness);
}

TEST(SimulationCli, PathWinsOverTheDefaults) {
  flight::FlightPath p = windyPath();
  const simulation::SimulationOptions o = resolveSimulationOptions({}, &p);
  EXPECT_EQ(o.wind.speedMps, 6.0);
  EXPECT_EQ(o.wind.directionDeg, 250.0);
  EXPECT_EQ(o.wind.gustiness, 0.6);
  p.wind->gustiness.reset();  // what the section leaves out stays the default
  EXPECT_EQ(resolveSimulationOptions({}, &p).wind.gustiness, simulation::WindOptions{}.gustiness);
}

TEST(SimulationCli, CommandLineWinsOverThePathsWindSection) {
  const flight::FlightPath p = windyPath();
  const simulation::SimulationOptions o = resolveSimulationOptions(parsed({"--wind-speed", "20"}), &p);
  EXPECT_EQ(o.wind.speedMps, 20.0) << "the command line wins";
  EXPECT_EQ(o.wind.directionDeg, 250.0) << "not given: the path's";
  EXPECT_EQ(o.wind.gustiness, 0.6);
  const simulation::SimulationOptions all = resolveSimulationOptions(
      parsed({"--wind-speed", "0", "--wind-direction", "90", "--gustiness", "1", "--trail-budget-mb", "4"}), &p);
  EXPECT_EQ(all.wind.speedMps, 0.0) << "a calm given on the command line wins too";
  EXPECT_EQ(all.wind.directionDeg, 90.0);
  EXPECT_EQ(all.wind.gustiness, 1.0);
  EXPECT_EQ(all.trailBudgetMb, 4.0);
}

TEST(SimulationCli, BadValuesNameTheOption) {
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--wind-speed", "101"}, "--wind-speed 101: must be 0 … 100 m/s"},
      {{"--wind-speed", "-1"}, "--wind-speed -1: must be 0 … 100 m/s"},
      {{"--wind-speed", "nan"}, "--wind-speed nan: must be 0 … 100 m/s"},
      {{"--wind-direction", "inf"}, "--wind-direction inf: must be a finite number of degrees"},
      {{"--gustiness", "-0.1"}, "--gustiness -0.1: must be 0 … 1"},
      {{"--gustiness", "1.5"}, "--gustiness 1.5: must be 0 … 1"},
      {{"--trail-budget-mb", "0"}, "--trail-budget-mb 0: must be more than 0"},
      {{"--trail-budget-mb", "-3"}, "--trail-budget-mb -3: must be more than 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args[0] + " " + c.args[1]);
    const Status s = checkSimulationOptions(parsed(c.args));
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().kind, ErrorKind::InvalidInput);
    EXPECT_EQ(s.error().message.rfind(c.message, 0), 0u) << s.error().message;
  }
  EXPECT_TRUE(checkSimulationOptions(parsed({"--wind-speed", "100", "--wind-direction", "-725", "--gustiness", "0",
                                             "--trail-budget-mb", "0.5"}))
                  .ok());
}

}  // namespace
}  // namespace vegstream::app
