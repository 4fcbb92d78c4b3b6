// Fixed-step playback (playback.h). Per frame: sample the path, run the frame through the
// driver, keep its record (the colour read-back, when asked for, is written as PNG and dropped);
// the table of named columns is built once at the end, so the per-frame bookkeeping
// (recorder_ms) stays a few hundred nanoseconds.

#include "scene/playback.h"

#include <cassert>
#include <cmath>
#include <cstdio>

#include "core/process_memory.h"
#include "core/stopwatch.h"
#include "flight/path_sampler.h"
#include "render/png_writer.h"
#include "scene/frame_table.h"

namespace vegstream::scene {

double fpsForFrames(double durationS, std::size_t frames) {
  assert(durationS > 0.0 && frames >= 1);
  if (frames == 1) return 0.5 / durationS;  // t = 0 only
  return static_cast<double>(frames - 1) / durationS;
}

Result<Recording> playFlight(FrameDriver& driver, const flight::FlightPath& path, const PlaybackOptions& options) {
  assert(options.fps > 0.0 && options.warmupS >= 0.0 && options.framesEvery >= 0);
  const flight::PathSampler sampler(path);
  const flight::GroundHeight ground = driver.scene().groundFunction();
  const std::size_t n = flight::frameCount(sampler.duration(), options.fps);

  Recording rec;
  rec.warmupFrames = static_cast<std::size_t>(std::llround(options.warmupS * options.fps));
  Stopwatch total;
  if (rec.warmupFrames > 0) {
    FrameInput start;
    start.pose = sampler.sample(0.0, ground);
    start.ahead = flight::lookAheadSamples(sampler, ground, 0.0);
    for (std::size_t i = 0; i < rec.warmupFrames; ++i)
      if (auto f = driver.run(start); !f) return f.error();
  }

  std::vector<FrameRecord> records;
  std::vector<double> wallMs, recorderMs, pngMs;
  records.reserve(n);
  wallMs.reserve(n);
  recorderMs.reserve(n);
  pngMs.reserve(n);
  FrameTableLayout layout;
  for (std::size_t i = 0; i < n; ++i) {
    Stopwatch frameWatch;
    const double t = std::min(static_cast<double>(i) / options.fps, sampler.duration());
    const bool savePng = options.framesEvery > 0 && i % static_cast<std::size_t>(options.framesEvery) == 0;

    Stopwatch stage;
    FrameInput input;
    input.timeS = t;
    input.pose = sampler.sample(t, ground);
    input.ahead = flight::lookAheadSamples(sampler, ground, t);
    input.flightMs = stage.elapsedMs();
    input.readbackColor = savePng;
    auto frame = driver.run(input);
    if (!frame) return frame.error();

    Stopwatch bookkeeping;
    if (i == 0) {
      rec.perPassMeaningful = frame->gpu.perPassMeaningful;
      rec.pipelineStatistics = frame->gpu.statistics.available;
      for (const render::PassTime& p : frame->gpu.passes) rec.gpuPasses.push_back(p.pass);
    }
    std::optional<render::ColorImage> color = std::move(frame->color);
    frame->color.reset();
    const double settleWaitMs = frame->scene.settleWaitMs;
    const double driverMs = frame->driverMs;
    records.push_back(std::move(*frame));
    recorderMs.push_back(driverMs + bookkeeping.elapsedMs());
    wallMs.push_back(frameWatch.elapsedMs() - settleWaitMs);

    pngMs.push_back(flight::kNoValue);
    if (savePng) {
      Stopwatch png;
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05zu.png", i);
      assert(color && "the renderer returns the colour read-back it was asked for");
      if (Status s = render::writePng(options.framesDir / name, *color); !s) return s.error();
      pngMs.back() = png.elapsedMs();
      ++rec.pngFrames;
    }
    if (options.progress) options.progress(i + 1, n);
  }

  layout.gpuPasses = rec.gpuPasses;
  layout.perPassMeaningful = rec.perPassMeaningful;
  rec.table = frameTable(records, wallMs, recorderMs, pngMs, layout);
  rec.wallS = total.elapsedMs() / 1000.0;
  rec.peakRssBytes = peakResidentBytes();
  return rec;
}

}  // namespace vegstream::scene
