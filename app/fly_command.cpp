#include "app/fly_command.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "app/dem_loader.h"
#include "app/exit_codes.h"
#include "core/atomic_file.h"
#include "core/stopwatch.h"
#include "flight/straight_flight.h"
#include "render/png_writer.h"
#include "render/renderer.h"
#include "terrain/grid_mesh.h"

namespace vegstream::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The demo path over the Zion sample: south-west to north-east across Zion Canyon, or the
// same diagonal of any other DEM's extent.
flight::StraightFlight demoFlight(const terrain::HeightGrid& grid, double durationS) {
  flight::StraightFlight f;
  const double lonW = grid.lonAt(0), lonE = grid.lonAt(grid.width - 1);
  const double latN = grid.latAt(0), latS = grid.latAt(grid.height - 1);
  f.start = {latS + 0.25 * (latN - latS), lonW + 0.40 * (lonE - lonW), 0.0};
  f.end = {latS + 0.55 * (latN - latS), lonW + 0.62 * (lonE - lonW), 0.0};
  f.altitudeAboveTerrainM = 650.0;
  f.pitchDeg = -14.0;
  f.durationS = durationS;
  return f;
}

bool displayAvailable() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

struct Window {
  GLFWwindow* handle = nullptr;
  ~Window() {
    if (handle) glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

}  // namespace

int runFly(const FlyOptions& options, const Logger& log) {
  auto grid = loadDemGrid(options.dataset);
  if (!grid) return reportError(log, grid.error());

  const bool windowed = !options.headless && displayAvailable() && glfwInit() == GLFW_TRUE;
  Window window;
  render::RendererOptions ro;
  ro.width = options.width;
  ro.height = options.height;
  ro.msaa = options.msaa;
  ro.context.deviceName = options.device;
  ro.context.validate = options.validate;
  ro.context.logger = log;
  ro.context.validationLog = std::make_shared<render::ValidationLog>();
  ro.context.validationLog->setListener([log](const std::string& m, bool isError) {
    if (isError) log->error("validation: {}", m); else log->warn("validation: {}", m);
  });
  if (windowed) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window.handle = glfwCreateWindow(static_cast<int>(options.width), static_cast<int>(options.height),
                                     "vegstream", nullptr, nullptr);
    ro.window = window.handle;
  }
  auto renderer = render::Renderer::create(ro);
  if (!renderer) return reportError(log, renderer.error());
  render::Renderer& r = **renderer;
  const auto& dev = r.device();
  log->info("device: {} ({}, {}, Vulkan {}, MSAA {})", dev.name, dev.type, dev.driver, dev.apiVersion, r.msaa());

  // The mesh is built only once every option has been checked, so a user mistake costs
  // nothing and prints nothing but its one message.
  const geo::LocalFrame frame({grid->centreLat(), grid->centreLon(), 0.0});
  Stopwatch meshWatch;
  const terrain::TerrainMesh mesh = terrain::buildGridMesh(*grid, frame, {options.meshStep});
  log->info("terrain: {}x{} DEM samples, {} triangles ({:.0f} ms)", grid->width, grid->height, mesh.triangleCount(),
            meshWatch.elapsedMs());
  if (auto s = r.setTerrain(mesh); !s) return reportError(log, s.error());

  const flight::StraightFlight path = demoFlight(*grid, options.durationS);
  auto ground = [&](double lat, double lon) { return grid->sampleLonLat(lon, lat); };
  auto request = [&](double t, bool readback, bool present) {
    const flight::FlightPose pose = flight::poseAt(path, t, frame, ground);
    render::FrameRequest req;
    req.camera = pose.camera;
    req.cameraHeightMsl = pose.position.heightM;
    req.readbackColor = readback;
    req.present = present;
    return req;
  };

  if (r.hasWindow()) {
    log->info("window open: the demo path loops; Esc or closing the window ends it");
    Stopwatch clock;
    int shown = 0;
    while (!glfwWindowShouldClose(window.handle) && glfwGetKey(window.handle, GLFW_KEY_ESCAPE) != GLFW_PRESS &&
           !(options.framesGiven && shown >= options.frames)) {
      glfwPollEvents();
      const double t = std::fmod(clock.elapsedMs() / 1000.0, options.durationS);
      if (auto f = r.renderFrame(request(t, false, true)); !f) return reportError(log, f.error());
      ++shown;
    }
    log->info("window closed after {} frames ({:.1f} frames/s)", shown, shown / std::max(clock.elapsedMs() / 1000.0, 1e-3));
    return kExitOk;
  }

  // Headless: PNG frames plus run.json with the device and per-frame figures.
  json frames = json::array();
  double sumCpu = 0.0, sumGpu = 0.0, sumWall = 0.0;
  uint64_t triangles = 0;
  const int n = options.frames;
  for (int i = 0; i < n; ++i) {
    Stopwatch wall;
    const double t = n > 1 ? options.durationS * i / (n - 1) : 0.0;
    auto result = r.renderFrame(request(t, true, false));
    if (!result) return reportError(log, result.error());
    const double wallMs = wall.elapsedMs();
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.png", i);
    if (auto s = render::writePng(fs::path(options.out) / name, *result->color); !s) return reportError(log, s.error());
    frames.push_back({{"index", i}, {"t_s", t}, {"cpu_record_ms", result->cpuRecordMs},
                      {"gpu_frame_ms", result->gpu.frameMs}, {"render_wall_ms", wallMs},
                      {"terrain_triangles", result->terrainTriangles}});
    sumCpu += result->cpuRecordMs;
    sumGpu += result->gpu.frameMs;
    sumWall += wallMs;
    triangles = result->terrainTriangles;
  }
  const json run = {
      {"device", {{"name", dev.name}, {"type", dev.type}, {"driver", dev.driver}, {"api_version", dev.apiVersion}}},
      {"dataset", fs::absolute(options.dataset).string()},
      {"size", {options.width, options.height}},
      {"msaa", r.msaa()},
      {"frames", n},
      {"terrain_triangles", triangles},
      {"per_pass_gpu_times_meaningful", !dev.software},
      {"mean_gpu_frame_ms", n ? sumGpu / n : 0.0},
      {"mean_cpu_record_ms", n ? sumCpu / n : 0.0},
      {"mean_render_wall_ms", n ? sumWall / n : 0.0},
      {"validation", {{"enabled", options.validate},
                      {"errors", ro.context.validationLog->errors()},
                      {"warnings", ro.context.validationLog->warnings()}}},
      {"per_frame", frames}};
  Status s = writeFileAtomically(fs::path(options.out) / "run.json", [&](const fs::path& tmp) -> Status {
    std::ofstream f(tmp);
    f << run.dump(2) << "\n";
    return f ? Status{} : makeError(ErrorKind::Io, "cannot write " + tmp.string());
  });
  if (!s) return reportError(log, s.error());
  log->info("{} frames of {}x{} written to {} (mean GPU frame {:.1f} ms, {} terrain triangles)", n, options.width,
            options.height, options.out, n ? sumGpu / n : 0.0, triangles);
  if (dev.software) log->info("{} is a CPU rasteriser: only frame-level GPU times are meaningful", dev.name);
  return kExitOk;
}

}  // namespace vegstream::app
