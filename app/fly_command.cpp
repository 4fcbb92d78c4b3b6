#include "app/fly_command.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "app/interactive_flight.h"
#include "app/sample_dataset.h"
#include "core/atomic_file.h"
#include "core/stopwatch.h"
#include "flight/flight_path_json.h"
#include "flight/path_templates.h"
#include "flight/scene.h"
#include "render/png_writer.h"

namespace vegstream::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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
// else the benchmark-30s template placed over the dataset.
Result<flight::FlightPath> choosePath(const std::optional<flight::FlightPath>& given, const flight::Scene& scene) {
  if (!given) return flight::makePathFromTemplate("benchmark-30s", scene.info().bounds, scene.groundFunction());
  if (Status s = flight::checkInside(*given, scene.info().bounds); !s) return s.error();
  return *given;
}

int runHeadless(const FlyOptions& o, flight::Scene& scene, const flight::FlightPath& path, const Logger& log,
                const render::ValidationLog& validation) {
  render::Renderer& r = scene.renderer();
  const flight::PathSampler sampler(path);
  const auto ground = scene.groundFunction();
  json frames = json::array();
  double sumGpu = 0.0, sumWall = 0.0;
  uint64_t triangles = 0;
  const int n = o.frames;
  for (int i = 0; i < n; ++i) {
    Stopwatch wall;
    const double t = n > 1 ? sampler.duration() * i / (n - 1) : 0.0;
    render::FrameRequest req =
        scene.prepareFrame(sampler.sample(t, ground), t, flight::lookAheadSamples(sampler, ground, t));
    const flight::SceneFrameFigures& fig = scene.lastFrameFigures();
    req.readbackColor = true;
    auto result = r.renderFrame(req);
    if (!result) return reportError(log, result.error());
    const double wallMs = wall.elapsedMs();
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.png", i);
    if (auto s = render::writePng(fs::path(o.out) / name, *result->color); !s) return reportError(log, s.error());
    frames.push_back({{"index", i}, {"t_s", t}, {"cpu_record_ms", result->cpuRecordMs},
                      {"gpu_frame_ms", result->gpu.frameMs}, {"render_wall_ms", wallMs},
                      {"terrain_triangles", result->terrainTriangles}, {"terrain_pieces", fig.terrain.pieces},
                      {"fallback_pieces", fig.terrain.fallbackPieces}, {"streaming_wait_ms", fig.settleWaitMs},
                      {"cpu_bytes", fig.cpuBytes}, {"gpu_bytes", fig.gpuBytes}});
    sumGpu += result->gpu.frameMs;
    sumWall += wallMs;
    triangles = result->terrainTriangles;
  }
  const auto& dev = r.device();
  const auto& info = scene.info();
  const json run = {
      {"device", {{"name", dev.name}, {"type", dev.type}, {"driver", dev.driver}, {"api_version", dev.apiVersion}}},
      {"dataset", {{"name", info.datasetName}, {"source", info.source}, {"min_zoom", info.minZoom},
                   {"max_zoom", info.maxZoom}, {"imagery", info.hasImagery}}},
      {"path", path.name},
      {"size", {o.width, o.height}},
      {"msaa", r.msaa()},
      {"frames", n},
      {"terrain_triangles", triangles},
      {"per_pass_gpu_times_meaningful", !dev.software},
      {"mean_gpu_frame_ms", n ? sumGpu / n : 0.0},
      {"mean_render_wall_ms", n ? sumWall / n : 0.0},
      {"validation", {{"enabled", o.validate}, {"errors", validation.errors()}, {"warnings", validation.warnings()}}},
      {"per_frame", frames}};
  Status s = writeFileAtomically(fs::path(o.out) / "run.json", [&](const fs::path& tmp) -> Status {
    std::ofstream f(tmp);
    f << run.dump(2) << "\n";
    return f ? Status{} : makeError(ErrorKind::Io, "cannot write " + tmp.string());
  });
  if (!s) return reportError(log, s.error());
  log->info("{} frames of {}x{} along '{}' written to {} (mean GPU frame {:.1f} ms, {} terrain triangles)", n, o.width,
            o.height, path.name, o.out, n ? sumGpu / n : 0.0, triangles);
  if (dev.software) log->info("{} is a CPU rasteriser: only frame-level GPU times are meaningful", dev.name);
  return kExitOk;
}

// The window: an interactive fly camera (app/interactive_flight.h) starting at the path's
// first pose; screenshots and recorded paths go to --out when given, else the current directory.
int runWindow(const FlyOptions& o, flight::Scene& scene, const flight::FlightPath& path, GLFWwindow* window,
              const Logger& log) {
  InteractiveOptions io;
  io.frames = o.framesGiven ? o.frames : 0;
  io.outDir = o.out == FlyOptions{}.out ? fs::path{} : fs::path(o.out);
  io.start = flight::sampleAt(path, 0.0, scene.groundFunction());
  return runInteractiveFlight(scene, window, withEnvironment(io), log);
}

}  // namespace

int runFly(const FlyOptions& o, const Logger& log) {
  flight::SceneOptions so;
  const bool windowWanted = !o.headless && displayAvailable();
  if (Status s = applyStreamingOptions(o.streaming, windowWanted ? flight::StreamingMode::Realtime
                                                                 : flight::StreamingMode::Settled, so); !s)
    return reportError(log, s.error());
  // A window flies in real time: ROAM's queue work stops after 2 ms a frame and carries on in the
  // next (recordings and headless frames stay deterministic, bounded by operations only).
  if (windowWanted) so.terrain.roam.maxQueueMs = 2.0;
  std::string dataset = o.dataset;
  if (dataset.empty()) {
    auto sample = ensureZionSample(o.samplesDir, "out/datasets/zion", log);
    if (!sample) return reportError(log, sample.error());
    dataset = sample->string();
  }

  std::optional<flight::FlightPath> given;
  if (!o.path.empty()) {
    auto loaded = flight::loadFlightPath(o.path);
    if (!loaded) return reportError(log, loaded.error());
    given = std::move(*loaded);
  }

  Window window;
  so.dataset = dataset;
  so.logger = log;
  so.renderer.width = o.width;
  so.renderer.height = o.height;
  so.renderer.msaa = o.msaa;
  so.renderer.context.deviceName = o.device;
  so.renderer.context.validate = o.validate;
  so.renderer.context.logger = log;
  auto validation = std::make_shared<render::ValidationLog>();
  validation->setListener([log](const std::string& m, bool isError) {
    if (isError) log->error("validation: {}", m); else log->warn("validation: {}", m);
  });
  so.renderer.context.validationLog = validation;
  if (windowWanted && glfwInit() == GLFW_TRUE) {
    window.initialised = true;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window.handle = glfwCreateWindow(static_cast<int>(o.width), static_cast<int>(o.height), "vegstream", nullptr, nullptr);
    so.renderer.window = window.handle;
  }
  auto scene = flight::Scene::open(so);
  if (!scene) return reportError(log, scene.error());
  auto path = choosePath(given, **scene);
  if (!path) return reportError(log, path.error());
  const flight::SceneInfo& info = (*scene)->info();
  log->info("dataset {} from {}: zooms {}…{}{}, {} streaming (opened in {:.0f} ms)", info.datasetName, info.source,
            info.minZoom, info.maxZoom, info.hasImagery ? " with imagery" : "", toString(so.mode), info.loadMs);
  const auto& dev = (*scene)->renderer().device();
  log->info("device: {} ({}, {}, Vulkan {}, MSAA {})", dev.name, dev.type, dev.driver, dev.apiVersion,
            (*scene)->renderer().msaa());
  if ((*scene)->renderer().hasWindow()) return runWindow(o, **scene, *path, window.handle, log);
  return runHeadless(o, **scene, *path, log, *validation);
}

}  // namespace vegstream::app
