#include "app/interactive_flight.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <string>

#include <GLFW/glfw3.h>

#include "app/camera_collider.h"
#include "app/exit_codes.h"
#include "app/fly_camera.h"
#include "app/hud.h"
#include "app/imgui_overlay.h"
#include "app/path_recorder.h"
#include "app/time_of_day.h"
#include "app/wind_controls.h"
#include "app/window_input.h"
#include "core/stopwatch.h"
#include "flight/flight_path.h"
#include "render/png_writer.h"
#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::app {
namespace fs = std::filesystem;

namespace {
constexpr size_t kGraphFrames = 120;
constexpr double kMessageSeconds = 4.0;

// Over the dataset, south of its centre, looking north and a little down.
flight::FlightSample defaultStart(const scene::Scene& scene) {
  const geo::GeoBounds& b = scene.info().bounds;
  flight::FlightSample s;
  s.position.latDeg = b.southDeg + 0.3 * b.heightDeg();
  s.position.lonDeg = b.westDeg + 0.5 * b.widthDeg();
  double ground = scene.groundHeight(s.position.latDeg, s.position.lonDeg);
  if (!std::isfinite(ground)) ground = 0.0;
  s.position.heightM = ground + 400.0;
  s.headingDeg = 0.0;
  s.pitchDeg = -15.0;
  return s;
}

// The last frame's figures on the HUD, read by the columns the stages declare
// (scene/frame_figures.h); before the first frame, an empty record's.
void putFrameFigures(HudState& s, const scene::FigureLookup& figure, const scene::FrameRecord* last) {
  static const scene::FrameRecord kNone{};
  const scene::FrameRecord& r = last ? *last : kNone;
  const auto n = [&](const char* column) { return static_cast<unsigned long long>(figure(r, column)); };
  if (last) {
    s.gpu = last->gpu;
    s.terrainTriangles = n("terrain_triangles");
    s.seedTriangles = n("terrain_seed_triangles");
    // The triangles the species pipelines drew (or the compute blade path counted).
    const double plantTriangles = figure(r, "plant_triangles");
    if (!std::isnan(plantTriangles)) s.plantTriangles = static_cast<uint64_t>(plantTriangles);
    s.cpuFrameMs = figure(r, "cpu_frame_ms");
    const double simulationMs = figure(r, "cpu_simulation_ms");
    if (std::isfinite(simulationMs)) s.cpuSimulationMs = simulationMs;
  }
  // Plants classified on the GPU, where their counts were read back.
  if (last && last->vegetation && last->vegetation->gpuCounts) s.plants = last->vegetation->plantsTotal;
  char line[256];
  std::snprintf(line, sizeof(line),
                "tiles %llu CPU / %llu GPU, %llu in flight, wanted %llu/%llu; %llu fallback pieces (%d lv), "
                "error %.1f px (x%.2f)",
                n("stream_tiles_resident_cpu"), n("stream_tiles_resident_gpu"), n("stream_requests_in_flight"),
                n("stream_wanted_resident"), n("stream_wanted"), n("terrain_fallback_pieces"),
                static_cast<int>(figure(r, "terrain_max_levels_coarser")), figure(r, "terrain_error_bound_px"),
                figure(r, "terrain_error_relaxation"));
  s.streaming = line;
  s.cpuBytes = n("cpu_bytes");
  s.gpuBytes = n("gpu_bytes");
}

// "20250102-130405": local time, for file names that sort by time.
std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y%m%d-%H%M%S", &tm);
  return buf;
}

class Session {
 public:
  Session(scene::Scene& scene, GLFWwindow* window, const InteractiveOptions& options, const Logger& log)
      : scene_(scene), window_(window), options_(options), log_(log),
        start_(options.start ? *options.start : defaultStart(scene)),
        camera_(scene.frame(), scene.groundFunction(), scene.frame().toLocal(start_.position), start_.headingDeg,
                start_.pitchDeg),
        input_(window), driver_(scene), collider_(options.collider), showHud_(options.hud) {
    if (options.path &&
        (!options.path->colliders.empty() || (options.path->wind && !options.path->wind->sources.empty())))
      pathSampler_.emplace(*options.path);
  }

  int run();

 private:
  void handleActions(const WindowActions& a, double now);
  void toggleRecording(double now);
  void sayCollider(double now);
  Status collect(uint64_t index, bool screenshot);
  void say(const std::string& text, double now, bool warn = false);
  fs::path outputPath(const std::string& name) const;
  HudState hudState(double now) const;

  scene::FrameInput frameInput();
  void addSimulationInputs(scene::FrameInput& input) const;

  scene::Scene& scene_;
  GLFWwindow* window_;
  InteractiveOptions options_;
  Logger log_;
  flight::FlightSample start_;
  FlyCamera camera_;
  WindowInput input_;
  scene::FrameDriver driver_;
  ImGuiOverlay overlay_;
  PathRecorder recorder_;
  std::optional<flight::PathSampler> pathSampler_;  // only when the path has colliders or wind sources
  CameraColliderMode collider_;
  bool showHud_ = true;
  bool showHelp_ = false;
  bool screenshotWanted_ = false;
  int screenshots_ = 0;
  std::deque<float> frameTimes_;
  std::optional<scene::FrameRecord> last_;            // the last frame collected
  const scene::FigureLookup figures_{scene::FigureLayout{}};  // its figures by column (no pass's)
  std::optional<flight::FlightSample> previousPose_;  // for velocity extrapolation (look-ahead)
  double previousPoseS_ = 0.0;
  std::string message_;
  double messageUntil_ = 0.0;
  double nowS_ = 0.0;
};

void Session::say(const std::string& text, double now, bool warn) {
  if (warn)
    log_->warn("{}", text);
  else
    log_->info("{}", text);
  message_ = text;
  messageUntil_ = now + kMessageSeconds;
}

fs::path Session::outputPath(const std::string& name) const {
  const fs::path dir = options_.outDir.empty() ? fs::current_path() : options_.outDir;
  std::error_code ec;
  fs::create_directories(dir, ec);  // a failure shows up when the file is written
  return dir / name;
}

void Session::toggleRecording(double now) {
  if (!recorder_.recording()) {
    recorder_.start(now, camera_.sample());
    say("recording the flight path (R stops)", now);
    return;
  }
  const std::string name = "flight-" + timestamp();
  auto path = recorder_.stop(now, camera_.sample(), name);
  if (!path) return say("path not saved: " + path.error().message, now, true);
  const fs::path file = outputPath(name + ".json");
  if (Status s = saveFlightPath(*path, file); !s) return say("path not saved: " + s.error().message, now, true);
  say("flight path saved: " + file.string() + " (" + std::to_string(path->keyframes.size()) + " keyframes)", now);
  if (Status inside = flight::checkInside(*path, scene_.info().bounds); !inside)
    log_->warn("`vegstream record` will refuse it: {}", inside.error().message);
}

void Session::sayCollider(double now) {
  if (collider_ == CameraColliderMode::Off) return say("camera collider: off", now);
  const CameraColliderShape c = cameraColliderShape(collider_);
  char line[128];
  std::snprintf(line, sizeof(line), "camera collider: %s (radius %.2f m, length %.1f m, %.1f m ahead)",
                cameraColliderName(collider_), c.radiusM, c.lengthM, c.aheadM);
  say(line, now);
}

void Session::handleActions(const WindowActions& a, double now) {
  if (a.toggleFollow) {
    camera_.setFollowTerrain(!camera_.followTerrain());
    say(camera_.followTerrain() ? "follow terrain on" : "follow terrain off", now);
  }
  if (a.toggleHelp) showHelp_ = !showHelp_;
  if (a.toggleHud) showHud_ = !showHud_;
  if (a.screenshot) screenshotWanted_ = true;
  if (a.toggleRecord) toggleRecording(now);
  if (a.cycleCollider) {
    collider_ = nextCameraColliderMode(collider_);
    sayCollider(now);
  }
  if (a.time.any()) {
    scene_.setStartDatetime(stepTime(scene_.sunClock().start, a.time));
    say("time: " + describeSun(scene_.sunClock().at(now), scene_.sunClock().sunAt(now)), now);
  }
  if (a.wind.any()) {
    const simulation::WindOptions wind = stepWind(driver_.simulation().options().wind, a.wind);
    driver_.setWind(wind);
    say("wind: " + describeWind(wind), now);
  }
}

Status Session::collect(uint64_t index, bool screenshot) {
  auto result = driver_.collect(index);
  if (!result) return result.error();
  if (screenshot && result->color) {
    char counter[16];
    std::snprintf(counter, sizeof(counter), "-%03d", ++screenshots_);
    const fs::path file = outputPath("vegstream-" + timestamp() + counter + ".png");
    if (Status s = render::writePng(file, *result->color); !s)
      say("screenshot failed: " + s.error().message, nowS_, true);
    else
      say("screenshot saved: " + file.string(), nowS_);
  }
  result->color.reset();
  last_ = std::move(*result);
  return {};
}

HudState Session::hudState(double now) const {
  const scene::SceneInfo& info = scene_.info();
  HudState s;
  s.datasetName = info.datasetName;
  s.deviceName = scene_.renderer().device().name;
  s.frameTimesMs.assign(frameTimes_.begin(), frameTimes_.end());
  double sum = 0.0;
  for (float ms : frameTimes_) sum += ms;
  s.fps = sum > 0.0 ? 1000.0 * static_cast<double>(frameTimes_.size()) / sum : 0.0;
  putFrameFigures(s, figures_, last_ ? &*last_ : nullptr);
  const flight::FlightSample pose = camera_.sample();
  s.latDeg = pose.position.latDeg;
  s.lonDeg = pose.position.lonDeg;
  s.altMslM = pose.position.heightM;
  s.aglM = pose.heightAboveGroundM;
  s.headingDeg = pose.headingDeg;
  s.pitchDeg = pose.pitchDeg;
  s.speedMps = camera_.speedMps();
  s.followTerrain = camera_.followTerrain();
  s.recording = recorder_.recording();
  s.recordingS = recorder_.elapsedS(now);
  s.recordedKeyframes = recorder_.keyframeCount();
  if (now < messageUntil_) s.message = message_;
  s.showHelp = showHelp_;
  const simulation::SimulationOptions& sim = driver_.simulation().options();
  s.simulationOn = sim.enabled;
  s.wind = sim.wind;
  s.cameraCollider = cameraColliderName(collider_);
  const scene::SunClock& sun = scene_.sunClock();
  s.sun = describeSun(sun.at(now), sun.sunAt(now));
  s.timeOfDayH = localHours(sun.at(now));
  if (pathSampler_) {
    s.pathColliders = pathSampler_->colliderCount();
    s.pathWindSources = pathSampler_->windSourceCount();
  }
  return s;
}

// Interactive flight cannot know where the user goes next: the look-ahead extrapolates the
// camera's velocity over the next seconds.
scene::FrameInput Session::frameInput() {
  Stopwatch watch;
  const flight::FlightSample now = camera_.sample();
  scene::FrameInput input;
  std::vector<flight::FlightSample>& ahead = input.ahead;
  if (previousPose_ && nowS_ > previousPoseS_) {
    const double dt = nowS_ - previousPoseS_;
    const double dLat = (now.position.latDeg - previousPose_->position.latDeg) / dt;
    const double dLon = (now.position.lonDeg - previousPose_->position.lonDeg) / dt;
    const double dH = (now.position.heightM - previousPose_->position.heightM) / dt;
    for (double k : {0.5, 1.0, 2.0, 3.0}) {
      flight::FlightSample s = now;
      s.position.latDeg += dLat * k;
      s.position.lonDeg += dLon * k;
      s.position.heightM += dH * k;
      ahead.push_back(s);
    }
  }
  previousPose_ = now;
  previousPoseS_ = nowS_;
  input.pose = now;
  input.timeS = nowS_;
  input.adaptExposure = true;  // only the window smooths the exposure over time
  addSimulationInputs(input);
  input.flightMs = watch.elapsedMs();
  return input;
}

// The path's colliders and wind sources at session time, as playback samples them at flight
// time (scene/playback.cpp), and the camera's collider after them: the simulation takes the
// first kMaxColliders, so a path that already fills them keeps its own.
void Session::addSimulationInputs(scene::FrameInput& input) const {
  const flight::GroundHeight ground = scene_.groundFunction();
  if (pathSampler_) {
    for (std::size_t i = 0; i < pathSampler_->colliderCount(); ++i)
      input.colliders.push_back(pathSampler_->collider(i, nowS_, ground));
    for (std::size_t i = 0; i < pathSampler_->windSourceCount(); ++i)
      input.windSources.push_back(pathSampler_->windSource(i, nowS_, ground));
  }
  if (auto c = cameraCollider(collider_, scene_.frame(), ground, input.pose.position, input.pose.headingDeg))
    input.colliders.push_back(*c);
}

int Session::run() {
  render::Renderer& renderer = scene_.renderer();
  log_->info("window open: right mouse button looks, WASD/QE fly, wheel sets speed, F1 help; Esc or closing ends it");
  if (collider_ != CameraColliderMode::Off) sayCollider(0.0);
  Stopwatch clock;
  double lastS = 0.0;
  int shown = 0;
  // Submitted, not collected, oldest first: index, screenshot. The driver refuses more than the
  // renderer's slots; framesInFlight may keep fewer (1: the serial loop, for comparison).
  std::deque<std::pair<uint64_t, bool>> inFlight;
  const std::size_t depth =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(options_.framesInFlight, 1)), 1,
                              scene::FrameDriver::kMaxInFlight);
  while (!glfwWindowShouldClose(window_) && !(options_.frames > 0 && shown >= options_.frames)) {
    glfwPollEvents();
    WindowActions actions;
    const FlyInput in = input_.poll(actions);
    if (actions.quit) break;
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    if (fbw == 0 || fbh == 0) {  // minimised: nothing to present to
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    nowS_ = clock.elapsedMs() / 1000.0;
    const double dt = nowS_ - lastS;
    lastS = nowS_;
    if (shown > 0) {
      frameTimes_.push_back(static_cast<float>(dt * 1000.0));
      if (frameTimes_.size() > kGraphFrames) frameTimes_.pop_front();
    }
    camera_.update(in, shown > 0 ? dt : 0.0);
    handleActions(actions, nowS_);
    if (recorder_.recording()) recorder_.add(nowS_, camera_.sample());
    if (options_.screenshotAtFrame == shown + 1) screenshotWanted_ = true;

    scene::FrameInput input = frameInput();
    input.present = true;
    input.readbackColor = screenshotWanted_;
    if (showHud_) {
      overlay_.begin(static_cast<float>(renderer.width()), static_cast<float>(renderer.height()), dt, input_.pointer());
      const HudEdits edits = drawHud(hudState(nowS_));
      input.overlay = &overlay_.end();
      if (edits.wind) driver_.setWind(*edits.wind);  // this frame's step already uses it
      // The slider's time of day: this frame's sun already (its lighting is prepared on submit).
      if (edits.timeOfDayH)
        scene_.setStartDatetime(geo::addSeconds(atLocalHours(scene_.sunClock().at(nowS_), *edits.timeOfDayH), -nowS_));
    }
    auto index = driver_.submit(input);
    if (!index) return reportError(log_, index.error());
    inFlight.emplace_back(*index, screenshotWanted_);
    screenshotWanted_ = false;
    ++shown;
    // Keep depth − 1 frames drawing while the next one is prepared (acquire waits for a
    // swapchain image; each slot has its own image-acquired semaphore, each image its own
    // render-done one, so up to kFramesInFlight presents may be queued).
    while (inFlight.size() >= depth) {
      const auto [oldest, screenshot] = inFlight.front();
      inFlight.pop_front();
      if (Status s = collect(oldest, screenshot); !s) return reportError(log_, s.error());
    }
  }
  while (!inFlight.empty()) {
    const auto [oldest, screenshot] = inFlight.front();
    inFlight.pop_front();
    if (Status s = collect(oldest, screenshot); !s) return reportError(log_, s.error());
  }
  if (recorder_.recording()) toggleRecording(clock.elapsedMs() / 1000.0);  // never lose a recording
  log_->info("window closed after {} frames ({:.1f} frames/s)", shown,
             shown / std::max(clock.elapsedMs() / 1000.0, 1e-3));
  return kExitOk;
}
}  // namespace

InteractiveOptions withEnvironment(InteractiveOptions options) {
  if (const char* n = std::getenv("VEGSTREAM_FLY_SCREENSHOT_FRAME"); n && *n)
    options.screenshotAtFrame = std::max(0, std::atoi(n));
  if (const char* h = std::getenv("VEGSTREAM_FLY_NO_HUD"); h && *h && std::string(h) != "0") options.hud = false;
  if (const char* c = std::getenv("VEGSTREAM_FLY_COLLIDER"); c && *c) {
    const std::string mode = c;
    if (mode == "walking") options.collider = CameraColliderMode::Walking;
    if (mode == "driving") options.collider = CameraColliderMode::Driving;
  }
  return options;
}

int runInteractiveFlight(scene::Scene& scene, GLFWwindow* window, const InteractiveOptions& options,
                         const Logger& log) {
  Session session(scene, window, options, log);
  return session.run();
}

}  // namespace vegstream::app
