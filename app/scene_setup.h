#pragma once
// What `fly` and `record` share between parsing and flying: the dataset they open (the Zion
// sample when none is given), the renderer options (size, MSAA, device, validation messages to
// the log), the lines they log when the scene is open, and — for headless `fly` and `record` —
// recording a path into a directory and reporting it. One definition, so both behave alike.

#include <cstdint>
#include <string>

#include "app/simulation_cli.h"
#include "app/streaming_cli.h"
#include "app/sun_cli.h"
#include "app/tree_cli.h"
#include "core/log.h"
#include "core/result.h"
#include "flight/flight_path.h"
#include "scene/recording_files.h"
#include "scene/scene.h"

namespace vegstream::app {

// The dataset to open: `given`, or the Zion sample imported once into out/datasets/zion; with
// `syntheticFallback` (fly), where the sample is missing, the synthetic dataset generated once
// into out/datasets/synthetic (sample_dataset.h).
Result<std::string> resolveDataset(const std::string& given, const std::string& samplesDir, const Logger& log,
                                   bool syntheticFallback = false);

// Registers the options `fly`, `record` and `snapshot` share on cmd, in this order: the streaming
// options (--streaming only `withMode`), the simulation's, the trees' and the sun's.
void addSceneOptions(CLI::App& cmd, StreamingCli& streaming, bool withMode, SimulationCli& simulation, TreeCli& trees,
                     SunCli& sun);

// The options `fly`, `record` and `snapshot` take first, before any file but --species is read:
// the streaming options (defaultMode where --streaming names none) and the tree options, checked
// against the catalog the scene will grow (--species, or the default).
Status applyStreamingAndTreeOptions(const StreamingCli& streaming, scene::StreamingMode defaultMode,
                                    const TreeCli& trees, scene::SceneOptions& so);

struct RendererCli {
  uint32_t width = 640, height = 360;
  int msaa = 4;
  std::string device;  // substring of a device name; empty: the best
  bool validate = false;
};

// Fills the scene's renderer options; validation messages go to the log as they arrive.
void applyRendererOptions(const RendererCli& cli, const Logger& log, scene::SceneOptions& so);

// "dataset … from …" and "device: …".
void logSceneOpened(const scene::Scene& scene, const Logger& log);

// Records `path` into request.out (scene/recording_files.h) and logs the outcome. Exit code: 0;
// 2 a user mistake; 1 a GPU/system failure, validation errors, or plots that could not be made
// (the recording itself is then written).
int recordAndReport(scene::Scene& scene, const flight::FlightPath& path, const scene::RecordingRequest& request,
                    const Logger& log);

}  // namespace vegstream::app
