#pragma once
// `vegstream snapshot [DATASET] --lat L --lon L --alt A --heading H --pitch P --out F.png
//  [--alt-ref ground|msl] [--size WxH] [--msaa N] [--device NAME] [--validate] [--time S]
//  [--datetime ISO] [--exposure EV] [--aov depth,coverage,species] [wind, plant, streaming and
//  terrain options of `record`]`: one still frame from a pose, as PNG, with its sidecar F.json
//  (scene/frame_sidecar.h: pose, field of view, date-time, sun, exposure, counts) and, with
//  --aov, the measurement AOVs F.depth.tif, F.coverage.tif, F.species.tif (scene/frame_aovs.h).
//
// --datetime sets the sun (scene/sun_clock.h; default: the imagery's acquisition time, else 10:00
// local mean solar time on 21 June 2024); the sun stays at that date-time while the still settles.
//
// --time S shows the shared simulation (wind, gusts) as it is S seconds into a flight that has
// stood at the pose since time 0: the same command always gives the same image.
//
// The pose follows flight paths (flight/flight_path.h, DESIGN.md "Flight paths"): --alt is metres
// above the ground under the camera (the ground mosaic scripted paths are resolved against), or
// above sea level with --alt-ref msl; heading in degrees clockwise from north, pitch in degrees
// (0 level, negative looks down). Streaming is settled and the still is taken only once the
// scene has settled at the pose (app/settled_still.h): the finest tiles the view wants, no
// geomorph or imagery fade under way. Every option, the dataset and the pose are checked before
// the GPU is touched where they can be; the PNG and its sidecar are each written to a temporary
// file beside --out and renamed into place when complete (the sidecar only once the PNG is).

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

struct SnapshotOptions {
  std::string dataset;     // directory or http(s) URL; empty: the Zion sample (imported once)
  std::string samplesDir;  // where the shared sample data lives (for the default)
  double latDeg = 0.0, lonDeg = 0.0;
  double altM = 0.0;
  std::string altRef = "ground";  // ground | msl
  double headingDeg = 0.0;        // clockwise from north
  double pitchDeg = 0.0;          // negative looks down
  std::string out;                // F.png
  std::string size = "1280x720";
  int msaa = 4;
  std::string device;
  bool validate = false;
  StreamingCli streaming;  // the plant, streaming and terrain options of `record` (settled)
  TreeCli treeCli;              // --trees, --tree-horizon-m, --tree-budget-mb as given
  SimulationCli simulationCli;  // --wind-speed, --wind-direction, --gustiness, --trail-budget-mb as given
  SunCli sunCli;                // --datetime (the still's sun), --exposure as given
  // What the simulation runs with: simulationCli over the defaults (a still has no flight path);
  // filled by runSnapshot.
  simulation::SimulationOptions simulation;
  double timeS = 0.0;  // --time: the simulation as it is this many seconds into a flight held at the pose
  std::string aov;     // --aov: comma-separated AOV names (scene/frame_aovs.h)
};

CLI::App* addSnapshotCommand(CLI::App& cli, SnapshotOptions& options);

// Exit code: 0 written; 2 a user mistake (one message naming the option, nothing written);
// 1 a GPU/system failure, or validation errors (the still is then written all the same).
int runSnapshot(SnapshotOptions options, const Logger& log);

}  // namespace vegstream::app
