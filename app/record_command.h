#pragma once
// `vegstream record [DATASET] --path P --out DIR …`: a deterministic fixed-step flight along a
// path, written as a recording directory (frames.csv, recording.json, summary.json, plots,
// optional frames/*.png; README.md "Recordings"). Every option, the path and the dataset are
// checked before anything is rendered; the directory appears only when complete.

#include <cstdint>
#include <string>

#include "app/simulation_cli.h"
#include "app/sun_cli.h"
#include "app/tree_cli.h"
#include "app/streaming_cli.h"
#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct RecordOptions {
  std::string dataset;     // dataset directory or http(s) URL; empty: the Zion sample (imported once)
  std::string samplesDir;  // where the shared sample data lives (for the default)
  std::string path;        // flight path JSON (required)
  std::string out;         // recording directory to create (required; must not exist or be empty)
  std::string size = "640x360";
  int msaa = 4;
  double fps = 60.0;
  int framesEvery = 0;  // 0: no PNG frames
  std::string aov;      // --aov: the AOVs beside each saved frame (scene/frame_aovs.h)
  int framesInFlight = 3;  // 1 (serial, for comparison) … 3: frames prepared while the GPU draws
  double warmupS = 0.0;
  std::string device;
  bool validate = false;
  bool noPlots = false;    // skip the plots (frames.csv and the JSON files only)
  StreamingCli streaming;  // budgets, --streaming settled|realtime (default settled), look-ahead
  TreeCli treeCli;              // --trees, --tree-horizon-m, --tree-budget-mb as given
  SimulationCli simulationCli;  // --wind-speed, --wind-direction, --gustiness, --trail-budget-mb as given
  SunCli sunCli;                // --datetime, --exposure as given
  // What the simulation runs with: simulationCli over the path's wind section over the defaults
  // (resolveSimulationOptions); filled by runRecord once the path is read.
  simulation::SimulationOptions simulation;
};

CLI::App* addRecordCommand(CLI::App& cli, RecordOptions& options);

// --frames-in-flight N (1 … render::kFramesInFlight), shared by `record` and `fly`.
void addFramesInFlightOption(CLI::App& cmd, int& framesInFlight);

// Exit code: 0 done; 2 a user mistake (one message, nothing written); 1 a GPU/system failure,
// or the recording was written but its plots could not be made (python3/matplotlib missing).
int runRecord(RecordOptions options, const Logger& log);

// "WxH" → width, height, each 1 … 16384.
bool parseFrameSize(const std::string& text, uint32_t& width, uint32_t& height);

}  // namespace vegstream::app
