#pragma once
// `vegstream fly`: fly over a dataset — in a window when a display exists, else headless along
// a flight path, writing PNG frames and run.json to --out.

#include <string>

#include "app/simulation_cli.h"
#include "app/sun_cli.h"
#include "app/tree_cli.h"
#include "app/streaming_cli.h"
#include "core/log.h"

namespace vegstream::app {

struct FlyOptions {
  std::string dataset;          // a dataset directory or http(s) URL; empty: the Zion sample
  std::string samplesDir;       // where the shared sample data lives (for the default)
  std::string path;             // flight path JSON; empty: the benchmark-30s template
  std::string out = "out/fly";  // headless output directory
  int frames = 96;
  bool framesGiven = false;  // --frames on the command line: a window closes after that many
  uint32_t width = 640, height = 360;
  int msaa = 4;
  int framesInFlight = 3;  // --frames-in-flight: headless playback and the window alike
  std::string device;  // --device NAME (substring)
  bool validate = false;
  bool headless = false;   // never open a window, even with a display
  StreamingCli streaming;  // --streaming default: settled headless (frames to look at), realtime in a window
  TreeCli treeCli;              // --trees, --tree-horizon-m, --tree-budget-mb as given
  SimulationCli simulationCli;  // --wind-speed, --wind-direction, --gustiness, --trail-budget-mb as given
  SunCli sunCli;                // --datetime, --exposure as given
  // What the simulation runs with: simulationCli over --path's wind section over the defaults
  // (resolveSimulationOptions); filled by runFly once --path is read, before the scene opens
  // (the default paths have no wind section).
  simulation::SimulationOptions simulation;
};

// Returns the process exit code: 0 success, 2 user mistake, 1 anything else.
int runFly(FlyOptions options, const Logger& logger);

}  // namespace vegstream::app
