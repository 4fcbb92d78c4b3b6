#pragma once
// A recording's directory and its two JSON files. recording.json holds what frames.csv cannot
// say (device, size, MSAA, fps, path, dataset, validation, peak RSS); summary.json is derived
// from recording.json + frames.csv — percentiles of every time column, hitches, peak memory,
// totals — so `vegstream report` can remake it at any time. README.md "Recordings" documents
// every key; other tools read them, so they stay stable.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "flight/record_table.h"

namespace vegstream::flight {

inline constexpr const char* kFramesCsv = "frames.csv";
inline constexpr const char* kRecordingJson = "recording.json";
inline constexpr const char* kSummaryJson = "summary.json";
inline constexpr const char* kFramesDir = "frames";

// Hitch rule: cpu_frame_ms + gpu_frame_ms over kHitchFactor × the median of the previous
// kHitchWindow frames (fewer at the start; frame 0 is never a hitch).
inline constexpr double kHitchFactor = 2.0;
inline constexpr std::size_t kHitchWindow = 60;

// The device a recording was drawn with, as recording.json names it (filled from the renderer's
// own description by scene/; flight/ knows no renderer).
struct RecordingDevice {
  std::string name, type, driver, apiVersion;
  bool software = false;  // a CPU rasteriser: per-pass GPU times mean nothing
};

struct RecordingMeta {
  RecordingDevice device;
  uint32_t width = 0, height = 0;
  int msaa = 1;
  std::string terrainShading;  // forward | deferred (what the renderer chose)
  double fps = 60.0;
  double warmupS = 0.0;
  std::size_t warmupFrames = 0;
  int framesEvery = 0;
  int framesInFlight = 1;  // frames the playback kept in flight (1: serial); the wall times depend on it
  std::string pathName, pathFile;
  double pathDurationS = 0.0;
  std::string datasetName, datasetDir;
  std::string datasetSource;                             // "dir …" or the URL tiles were streamed from
  int heightZoom = 0, imageryZoom = -1, groundZoom = 0;  // finest zooms streamed; the ground mosaic's
  double sceneLoadMs = 0.0;
  struct Streaming {
    std::string mode;  // "settled" or "realtime"
    bool lookAhead = true;
    uint64_t cpuBudgetBytes = 0, gpuBudgetBytes = 0, uploadBytesPerFrame = 0;
    int maxRequestsInFlight = 0;
    uint32_t imageryLayers = 0;
    double terrainErrorPx = 0.0;
    int terrainMaxNodes = 0;
    uint64_t terrainMaxTriangles = 0;
    double canopyM = 0.0, seedHorizonM = 0.0;
    double terrainDetail = 1.0;  // strength of the close-up detail textures
    int seedLevel = 0;
    double seedTriangleAreaM2 = 0.0;
  } streaming;
  struct Plants {
    bool enabled = false;
    double density = 0.0, maxPerTriangle = 0.0;  // ρ (per pixel² of a 1080-line view), n_max (eq. 1)
    double groundDensityM2 = 0.0;                // the densest species' plants per m²
    bool fades = true;                           // false: --plant-fades off
    uint32_t clusterSize = 0;
    std::string speciesCatalog;  // the file, or "default"
    std::string style;           // plants | markers | hidden
    uint32_t maxSegments = 0;    // n_max segments of a blade (eq. 4)
    double lodDistanceM = 0.0;   // eq. 4's distance unit
    bool shadows = false;
    double shadowDistanceM = 0.0;  // planar shadows fade out over its last quarter
    bool occlusionCulling = false;  // Hi-Z culling of hidden seed triangles
    std::string bladePath;           // how plants became triangles: tessellation | compute (render/README.md)
    std::string bladePathRequested;  // --blade-path: auto | tessellation | compute
    std::vector<std::string> species;  // names, in catalog order
  } plants;
  // The sun at flight time 0 (issue 39; frames.csv's sun_* columns follow it over the flight).
  struct Sun {
    std::string datetime;               // ISO 8601, in the offset it was given in
    std::string datetimeSource;         // option (--datetime or the path) | dataset (imagery.datetime) | default
    double latDeg = 0.0, lonDeg = 0.0;  // seen from: the dataset's centre
    double azimuthDeg = 0.0, elevationDeg = 0.0;
  } sun;
  std::optional<double> exposureEv;  // --exposure (EV100); absent: automatic
  bool validate = false;
  uint64_t validationErrors = 0, validationWarnings = 0;
  bool perPassMeaningful = false;
  bool pipelineStatistics = false;
  std::vector<std::string> gpuPasses;
  double wallS = 0.0;
  uint64_t peakRssBytes = 0;
};

// recording.json's text.
std::string recordingMetaJson(const RecordingMeta& meta);

// Linear-interpolated percentile (q in [0, 100]) of unsorted values, as numpy's default; NaN
// for none.
double percentile(std::vector<double> values, double q);

// Indices of the hitch frames (rule above) given each frame's time in ms.
std::vector<std::size_t> findHitches(const std::vector<double>& frameMs);

// summary.json's text from recording.json's text and the frames.
Result<std::string> makeSummaryJson(const std::string& recordingJson, const std::string& recordingSource,
                                    const RecordTable& frames);

// Reads DIR/recording.json and DIR/frames.csv and (re)writes DIR/summary.json atomically.
// NotFound / InvalidInput name the file.
Status writeSummary(const std::filesystem::path& dir);

}  // namespace vegstream::flight
