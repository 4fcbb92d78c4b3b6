// Fixed-step playback (playback.h). Per frame: sample the path, submit the frame through the
// driver, and — once framesInFlight frames are in flight — collect the oldest and keep its record
// (the colour read-back, when asked for, is written as PNG and dropped); the table of named
// columns is built once at the end, so the per-frame bookkeeping (recorder_ms) stays a few
// hundred nanoseconds.

#include "scene/playback.h"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <deque>

#include "core/process_memory.h"
#include "core/stopwatch.h"
#include "flight/path_sampler.h"
#include "scene/frame_sidecar.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

double fpsForFrames(double durationS, std::size_t frames) {
  assert(durationS > 0.0 && frames >= 1);
  if (frames == 1) return 0.5 / durationS;  // t = 0 only
  return static_cast<double>(frames - 1) / durationS;
}

namespace {

// The frames of one playback, submitted ahead and collected in order.
class Pipeline {
 public:
  // `total`: the frames to record (for the progress callback).
  Pipeline(FrameDriver& driver, const flight::PathSampler& sampler, const PlaybackOptions& options, std::size_t total,
           Recording& rec)
      : driver_(driver), sampler_(sampler), ground_(driver.scene().groundFunction()), options_(options), total_(total),
        rec_(rec) {}

  // Submits frame `frame` at flight time t (recorded: a row of frames.csv; else warm-up),
  // collecting the oldest first when framesInFlight are in flight.
  Status submit(std::size_t frame, double t, bool recorded) {
    if (pending_.size() >= options_.framesInFlight)
      if (Status s = collectOldest(); !s) return s;
    const bool savePng =
        recorded && options_.framesEvery > 0 && frame % static_cast<std::size_t>(options_.framesEvery) == 0;
    Stopwatch stage;
    FrameInput input;
    input.timeS = t;
    input.pose = sampler_.sample(t, ground_);
    input.ahead = flight::lookAheadSamples(sampler_, ground_, t);
    for (std::size_t i = 0; i < sampler_.colliderCount(); ++i) input.colliders.push_back(sampler_.collider(i, t, ground_));
    for (std::size_t i = 0; i < sampler_.windSourceCount(); ++i)
      input.windSources.push_back(sampler_.windSource(i, t, ground_));
    input.flightMs = stage.elapsedMs();
    input.readbackColor = savePng;
    auto index = driver_.submit(input);
    if (!index) return index.error();
    // A settled frame's wait for its tiles is not frame time, whichever frame it delays.
    excludedMs_ += driver_.scene().lastFrameFigures().settleWaitMs;
    pending_.push_back({frame, recorded, savePng, false});
    if (savePng && options_.aovs.any()) return submitAov(frame, std::move(input));
    return {};
  }

  // The saved frame's AOV frame: the same input again (playback.h PlaybackOptions::aovs).
  Status submitAov(std::size_t frame, FrameInput input) {
    if (pending_.size() >= options_.framesInFlight)
      if (Status s = collectOldest(); !s) return s;
    input.readbackColor = false;
    input.aov = true;
    auto index = driver_.submit(input);
    if (!index) return index.error();
    pending_.push_back({frame, false, false, true});
    return {};
  }

  // Collects every frame still in flight.
  Status drain() {
    while (!pending_.empty())
      if (Status s = collectOldest(); !s) return s;
    return {};
  }

  // Recording starts now: the first recorded frame's wall time is counted from here.
  void startClock() {
    lastDoneMs_ = clock_.elapsedMs();
    excludedMs_ = 0.0;
  }

  std::vector<FrameRecord> records;  // each with its row's recorder figures (FrameRecord::row …)

 private:
  struct Pending {
    std::size_t frame;
    bool recorded, savePng, aov;
  };

  static std::string frameName(std::size_t frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05zu.png", frame);
    return name;
  }

  Status collectOldest() {
    const Pending p = pending_.front();
    pending_.pop_front();
    auto frame = driver_.collect(driver_.oldestInFlight());
    if (!frame) return frame.error();
    if (p.aov) {  // written, and its time since the saved frame left out of the next one's
      if (!frame->aov) return makeError(ErrorKind::Internal, "the renderer returned no AOV read-back");
      if (Status s = writeFrameAovs(options_.framesDir / frameName(p.frame), *frame->aov, options_.aovs); !s) return s;
      lastDoneMs_ = clock_.elapsedMs();
      excludedMs_ = 0.0;
      return {};
    }
    if (!p.recorded) return {};
    assert(p.frame == records.size() && "frames are collected in order");

    Stopwatch bookkeeping;
    if (records.empty()) {
      rec_.perPassMeaningful = frame->gpu.perPassMeaningful;
      rec_.pipelineStatistics = frame->gpu.statistics.available;
      for (const render::PassTime& pass : frame->gpu.passes) rec_.gpuPasses.push_back(pass.pass);
    }
    std::optional<render::ColorImage> color = std::move(frame->color);
    frame->color.reset();
    const double driverMs = frame->driverMs;
    records.push_back(std::move(*frame));
    FrameRecord& record = records.back();
    record.row = p.frame;
    record.recorderMs = driverMs + bookkeeping.elapsedMs();
    // Completion to completion (playback.h): with frames in flight, the CPU work of the later
    // frames and the GPU work of this one overlap inside this interval.
    const double doneMs = clock_.elapsedMs();
    record.wallMs = doneMs - lastDoneMs_ - excludedMs_;
    lastDoneMs_ = doneMs;
    excludedMs_ = 0.0;

    if (p.savePng) {
      Stopwatch png;
      assert(color && "the renderer returns the colour read-back it was asked for");
      const std::string sidecar = frameSidecarJson(record, color->width, color->height, driver_.scene());
      if (Status s = writeFrameWithSidecar(options_.framesDir / frameName(p.frame), *color, sidecar); !s) return s.error();
      record.pngMs = png.elapsedMs();
      excludedMs_ += record.pngMs;
      ++rec_.pngFrames;
    }
    if (options_.progress) options_.progress(records.size(), total_);
    return {};
  }

  FrameDriver& driver_;
  const flight::PathSampler& sampler_;
  const flight::GroundHeight ground_;
  const PlaybackOptions& options_;
  const std::size_t total_;
  Recording& rec_;
  std::deque<Pending> pending_;  // submitted, oldest first (the driver's frames in flight)
  Stopwatch clock_;
  double lastDoneMs_ = 0.0;
  double excludedMs_ = 0.0;  // settled waits and PNG writing since the last completion
};

}  // namespace

Result<Recording> playFlight(FrameDriver& driver, const flight::FlightPath& path, const PlaybackOptions& options) {
  assert(options.fps > 0.0 && options.warmupS >= 0.0 && options.framesEvery >= 0);
  assert(options.framesInFlight >= 1 && options.framesInFlight <= FrameDriver::kMaxInFlight);
  assert(driver.framesInFlight() == 0 && "playback starts with no frame in flight");
  const flight::PathSampler sampler(path);
  // The ceiling before anything is reserved (the command line checked it already, naming the file).
  if (Status s = flight::checkRecordable(sampler.duration(), options.fps, options.warmupS, path.name); !s)
    return s.error();
  const std::size_t n = flight::frameCount(sampler.duration(), options.fps);

  Recording rec;
  rec.framesInFlight = options.framesInFlight;
  rec.warmupFrames = static_cast<std::size_t>(std::llround(options.warmupS * options.fps));
  Stopwatch total;
  Pipeline pipeline(driver, sampler, options, n, rec);
  // Warm-up frames go through the same pipeline and are drained before the recording starts, so
  // the first recorded frame finds the same (empty) pipeline whatever the warm-up.
  for (std::size_t i = 0; i < rec.warmupFrames; ++i)
    if (Status s = pipeline.submit(i, 0.0, false); !s) return s.error();
  if (Status s = pipeline.drain(); !s) return s.error();

  pipeline.records.reserve(n);
  pipeline.startClock();
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::min(static_cast<double>(i) / options.fps, sampler.duration());
    if (Status s = pipeline.submit(i, t, true); !s) return s.error();
  }
  if (Status s = pipeline.drain(); !s) return s.error();

  FigureLayout layout;
  layout.gpuPasses = rec.gpuPasses;
  layout.perPassMeaningful = rec.perPassMeaningful;
  rec.table = frameTable(pipeline.records, layout);
  rec.wallS = total.elapsedMs() / 1000.0;
  rec.peakRssBytes = peakResidentBytes();
  return rec;
}

}  // namespace vegstream::scene
