#pragma once
// `vegstream fly`: fly the demo path over a DEM — in a window when a display exists, else
// headless, writing PNG frames and run.json to --out.

#include <string>

#include "core/log.h"

namespace vegstream::app {

struct FlyOptions {
  std::string dataset;          // DEM GeoTIFF or a directory with srtm.tif
  std::string out = "out/fly";  // headless output directory
  int frames = 96;
  bool framesGiven = false;     // --frames on the command line: a window closes after that many
  uint32_t width = 640, height = 360;
  int msaa = 4;
  std::string device;           // --device NAME (substring)
  bool validate = false;
  bool headless = false;        // never open a window, even with a display
  double durationS = 12.0;      // flight time covered by the frames
  int meshStep = 1;             // use every N-th DEM sample
};

// Returns the process exit code: 0 success, 2 user mistake, 1 anything else.
int runFly(const FlyOptions& options, const Logger& logger);

}  // namespace vegstream::app
