#pragma once
// A recording directory (README.md "Recordings"): plays a path through the frame driver and
// writes frames.csv, recording.json, summary.json, the plots and the saved frames into a
// temporary directory that is renamed into place when complete — never half-written. `record`
// and headless `fly` both write their recordings here, so the two are the same format.

#include <filesystem>
#include <optional>
#include <string>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/summary.h"
#include "scene/playback.h"

namespace vegstream::scene {

struct RecordingRequest {
  std::filesystem::path out;  // the directory to create: must not exist, or be empty
  PlaybackOptions playback;   // framesDir is set to out/frames
  bool plots = true;          // run the matplotlib script (flight/report.h)
  // For recording.json, what the scene does not know:
  std::string pathFile;                    // the flight-path file ("" for a template placed over the dataset)
  std::string speciesCatalog = "default";  // the catalog file, or "default"
};

struct RecordingOutcome {
  Recording recording;
  // The plots could not be made (no python3 / matplotlib): everything else was written.
  std::optional<Error> plotError;
};

// recording.json's content for a recording of `path` through `scene`.
flight::RecordingMeta recordingMeta(const Scene& scene, const flight::FlightPath& path, const Recording& recording,
                                    const RecordingRequest& request);

// Plays `path` and writes the recording directory. Errors: a non-empty `out` (InvalidInput),
// GPU and I/O failures.
Result<RecordingOutcome> recordToDirectory(FrameDriver& driver, const flight::FlightPath& path,
                                           const RecordingRequest& request);

}  // namespace vegstream::scene
