#include "app/fly_command.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <GLFW/glfw3.h>
#include "app/exit_codes.h"
#include "app/interactive_flight.h"
#include "app/scene_setup.h"
#include "flight/flight_path_json.h"
#include "flight/path_templates.h"
#include "flight/summary.h"
#include "scene/playback.h"

namespace vegstream::app {
namespace fs = std::filesystem;

namespace {

constexpr double kFlyDefaultWindMps = 4.0;       // a gentle breeze, 10 m up
constexpr double kFlyDefaultWindFromDeg = 250.0;  // west-south-west, Utah's prevailing wind


bool displayAvailable() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

struct Window {
  GLFWwindow* handle = nullptr;
  bool initialised = false;
  ~Window() {
    if (handle) glfwDestroyWindow(handle);
    if (initialised) glfwTerminate();
  }
};

// The flight: the given path (read before the dataset is opened, checked against it after),
// else over a dataset of Zion (one that holds it: the sample, whatever its directory is called)
// its benchmark flight over the Kolob meadow (flight/paths/benchmark-30s.json, embedded), else
// the benchmark-30s template placed over the dataset.
Result<flight::FlightPath> choosePath(const std::optional<flight::FlightPath>& given, const scene::Scene& scene) {
  if (!given) {
    auto zion = flight::parseFlightPath(flight::zionBenchmarkPathJson(), "flight/paths/benchmark-30s.json");
    if (zion && flight::checkInside(*zion, scene.info().bounds)) return *zion;
  }
  if (!given) return flight::makePathFromTemplate("benchmark-30s", scene.info().bounds, scene.groundFunction());
  if (Status s = flight::checkInside(*given, scene.info().bounds); !s) return s.error();
  return *given;
}

// Headless frames are a recording like `record`'s (frames.csv, recording.json, summary.json,
// every frame as frames/frame_NNNNN.png): --frames N spread evenly over the path. `--out` may
// hold an earlier recording (the default out/fly does after the first run): it is replaced only
// once the new one is complete; anything else there is refused, never overwritten.
Status checkHeadlessOut(const FlyOptions& o) {
  const fs::path out = o.out;
  std::error_code ec;
  const bool earlier = fs::exists(out, ec) && !(fs::is_directory(out, ec) && fs::is_empty(out, ec));
  if (earlier && !fs::exists(out / flight::kRecordingJson, ec) && !fs::exists(out / "run.json", ec))
    return makeError(ErrorKind::InvalidInput,
                     "--out " + o.out + " already exists and holds no earlier recording; choose another directory");
  return {};
}

// `outChecked`: checkHeadlessOut already ran, before the scene was opened (a window was not wanted).
int runHeadless(const FlyOptions& o, scene::Scene& scene, const flight::FlightPath& path, const Logger& log,
                bool outChecked) {
  if (!outChecked)
    if (Status s = checkHeadlessOut(o); !s) return reportError(log, s.error());
  const fs::path out = o.out;
  std::error_code ec;
  const bool earlier = fs::is_directory(out, ec) && !fs::is_empty(out, ec);
  const fs::path aside = out.string() + ".replaced";
  if (earlier) {
    fs::remove_all(aside, ec);
    fs::rename(out, aside, ec);
    if (ec)
      return reportError(
          log, makeError(ErrorKind::Io, "cannot move the earlier recording " + o.out + " aside: " + ec.message()));
  }
  scene::RecordingRequest request;
  request.out = out;
  request.playback.fps = scene::fpsForFrames(path.duration(), static_cast<std::size_t>(o.frames));
  request.playback.framesEvery = 1;
  request.playback.framesInFlight = static_cast<std::size_t>(o.framesInFlight);
  request.plots = false;  // `vegstream report DIR` makes them
  request.pathFile = o.path;
  request.speciesCatalog = o.streaming.species.empty() ? "default" : o.streaming.species;
  const int code = recordAndReport(scene, path, request, log);
  if (earlier) {
    if (fs::exists(out / flight::kRecordingJson, ec))
      fs::remove_all(aside, ec);
    else
      fs::rename(aside, out, ec);  // nothing new was written: the earlier recording stays
  }
  return code;
}

// The window: an interactive fly camera (app/interactive_flight.h) starting at the path's
// first pose, the path's colliders and wind sources moving on session time; screenshots and
// recorded paths go to --out when given, else the current directory.
int runWindow(const FlyOptions& o, scene::Scene& scene, const flight::FlightPath& path, GLFWwindow* window,
              const Logger& log) {
  InteractiveOptions io;
  io.frames = o.framesGiven ? o.frames : 0;
  io.framesInFlight = o.framesInFlight;
  io.outDir = o.out == FlyOptions{}.out ? fs::path{} : fs::path(o.out);
  io.start = flight::sampleAt(path, 0.0, scene.groundFunction());
  io.path = path;
  return runInteractiveFlight(scene, window, withEnvironment(io), log);
}

}  // namespace

int runFly(FlyOptions o, const Logger& log) {
  scene::SceneOptions so;
  const bool windowWanted = !o.headless && displayAvailable();
  const auto mode = windowWanted ? scene::StreamingMode::Realtime : scene::StreamingMode::Settled;
  if (Status s = applyStreamingAndTreeOptions(o.streaming, mode, o.treeCli, so); !s)
    return reportError(log, s.error());
  if (Status s = checkSimulationOptions(o.simulationCli); !s) return reportError(log, s.error());
  auto sun = checkSunOptions(o.sunCli);
  if (!sun) return reportError(log, sun.error());
  // A window flies in real time: ROAM's queue work stops after 2 ms a frame and carries on in the
  // next (recordings and headless frames stay deterministic, bounded by operations only).
  if (windowWanted) so.terrain.roam.maxQueueMs = 2.0;
  if (!windowWanted)  // before the GPU is touched; a wanted window that cannot be made checks it later
    if (Status s = checkHeadlessOut(o); !s) return reportError(log, s.error());
  auto dataset = resolveDataset(o.dataset, o.samplesDir, log, true);
  if (!dataset) return reportError(log, dataset.error());

  std::optional<flight::FlightPath> given;
  if (!o.path.empty()) {
    auto loaded = flight::loadFlightPath(o.path);
    if (!loaded) return reportError(log, loaded.error());
    given = std::move(*loaded);
  }
  o.simulation = resolveSimulationOptions(o.simulationCli, given ? &*given : nullptr);
  // `fly` is the demo: where neither the command line nor the path says what the wind does, a
  // gentle west-south-west breeze moves the grass (record and snapshot stay calm by default, so
  // benchmarks and stills do not change under anyone's feet).
  const bool pathWind = given && given->wind && given->wind->speedMps;
  if (!o.simulationCli.windSpeedMps && !pathWind) {
    o.simulation.wind.speedMps = kFlyDefaultWindMps;
    if (!o.simulationCli.windDirectionDeg && !(given && given->wind && given->wind->directionDeg))
      o.simulation.wind.directionDeg = kFlyDefaultWindFromDeg;
  }

  Window window;
  so.dataset = *dataset;
  so.simulation = o.simulation;
  applySunOptions(*sun, given ? &*given : nullptr, so);
  applyRendererOptions({o.width, o.height, o.msaa, o.device, o.validate}, log, so);
  if (windowWanted && glfwInit() == GLFW_TRUE) {
    window.initialised = true;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window.handle =
        glfwCreateWindow(static_cast<int>(o.width), static_cast<int>(o.height), "vegstream", nullptr, nullptr);
    so.renderer.window = window.handle;
  }
  auto scene = scene::Scene::open(so);
  if (!scene) return reportError(log, scene.error());
  auto path = choosePath(given, **scene);
  if (!path) return reportError(log, path.error());
  logSceneOpened(**scene, log);
  if ((*scene)->renderer().hasWindow()) return runWindow(o, **scene, *path, window.handle, log);
  return runHeadless(o, **scene, *path, log, !windowWanted);
}

}  // namespace vegstream::app
