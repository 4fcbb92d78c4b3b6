// fly and record's shared setup and reporting (scene_setup.h).

#include "app/scene_setup.h"

#include <algorithm>
#include <memory>
#include <optional>

#include "app/exit_codes.h"
#include "app/sample_dataset.h"
#include "flight/summary.h"

namespace vegstream::app {

Result<std::string> resolveDataset(const std::string& given, const std::string& samplesDir, const Logger& log,
                                   bool syntheticFallback) {
  if (!given.empty()) return given;
  auto sample = syntheticFallback ? ensureDefaultDataset(samplesDir, "out/datasets/zion", "out/datasets/synthetic", log)
                                  : ensureZionSample(samplesDir, "out/datasets/zion", log);
  if (!sample) return sample.error();
  return sample->string();
}

void addSceneOptions(CLI::App& cmd, StreamingCli& streaming, bool withMode, SimulationCli& simulation, TreeCli& trees,
                     SunCli& sun) {
  addStreamingOptions(cmd, streaming, withMode);
  addSimulationOptions(cmd, simulation);
  addTreeOptions(cmd, trees);
  addSunOptions(cmd, sun);
}

Status applyStreamingAndTreeOptions(const StreamingCli& streaming, scene::StreamingMode defaultMode,
                                    const TreeCli& trees, scene::SceneOptions& so) {
  if (Status s = applyStreamingOptions(streaming, defaultMode, so); !s) return s;
  if (Status s = checkTreeOptions(trees, so.species ? *so.species : vegetation::defaultSpeciesCatalog()); !s) return s;
  applyTreeOptions(trees, so);
  return {};
}

void applyRendererOptions(const RendererCli& cli, const Logger& log, scene::SceneOptions& so) {
  so.logger = log;
  so.renderer.width = cli.width;
  so.renderer.height = cli.height;
  so.renderer.msaa = cli.msaa;
  so.renderer.context.deviceName = cli.device;
  so.renderer.context.validate = cli.validate;
  so.renderer.context.logger = log;
  auto validation = std::make_shared<render::ValidationLog>();
  validation->setListener([log](const std::string& m, bool isError) {
    if (isError)
      log->error("validation: {}", m);
    else
      log->warn("validation: {}", m);
  });
  so.renderer.context.validationLog = validation;
}

void logSceneOpened(const scene::Scene& scene, const Logger& log) {
  const scene::SceneInfo& info = scene.info();
  const scene::SceneOptions& so = scene.options();
  log->info("dataset {} from {}: zooms {}…{}{}, {} streaming{}, budgets CPU {:.0f} MiB, GPU {:.0f} MiB ({:.0f} ms)",
            info.datasetName, info.source, info.minZoom, info.maxZoom, info.hasImagery ? " with imagery" : "",
            toString(so.mode), so.lookAhead ? " with look-ahead" : " without look-ahead",
            static_cast<double>(so.streaming.cpuBudgetBytes) / (1024.0 * 1024.0),
            static_cast<double>(so.streaming.gpuBudgetBytes) / (1024.0 * 1024.0), info.loadMs);
  const render::DeviceInfo& dev = scene.renderer().device();
  log->info("device: {} ({}, {}, Vulkan {}, MSAA {}, {} terrain shading)", dev.name, dev.type, dev.driver,
            dev.apiVersion, scene.renderer().msaa(), render::terrainShadingName(scene.renderer().terrainShading()));
}

int recordAndReport(scene::Scene& scene, const flight::FlightPath& path, const scene::RecordingRequest& request,
                    const Logger& log) {
  const std::size_t total = flight::frameCount(path.duration(), request.playback.fps);
  log->info("recording {} ({:.1f} s) at {:.4g} fps: {} frames of {}x{}", path.name, path.duration(),
            request.playback.fps, total, scene.renderer().width(), scene.renderer().height());
  scene::RecordingRequest r = request;
  std::size_t nextReport = total / 10;
  r.playback.progress = [&](std::size_t done, std::size_t all) {
    if (done < nextReport || done == all) return;
    log->info("  {} / {} frames", done, all);
    nextReport += std::max<std::size_t>(all / 10, 1);
  };
  scene::FrameDriver driver(scene);
  auto outcome = scene::recordToDirectory(driver, path, r);
  if (!outcome) return reportError(log, outcome.error());

  const flight::RecordTable& t = outcome->recording.table;
  const auto gpu = t.values(*t.find("gpu_frame_ms")), cpu = t.values(*t.find("cpu_frame_ms"));
  const auto rec = t.values(*t.find("recorder_ms"));
  double cpuSum = 0.0, recSum = 0.0;
  for (double v : cpu) cpuSum += v;
  for (double v : rec) recSum += v;
  log->info("{} frames in {:.1f} s wall; GPU frame p50 {:.2f} ms, p95 {:.2f} ms; recorder {:.2f} % of the CPU frame",
            t.rowCount(), outcome->recording.wallS, flight::percentile(gpu, 50), flight::percentile(gpu, 95),
            cpuSum > 0.0 ? 100.0 * recSum / cpuSum : 0.0);
  const render::DeviceInfo& dev = scene.renderer().device();
  if (dev.software) log->info("{} is a CPU rasteriser: per-pass GPU times are left empty", dev.name);
  const render::ValidationLog* validation = scene.renderer().validationLog();
  const int validationErrors = validation ? validation->errors() : 0;
  if (validationErrors > 0) log->error("validation reported {} errors", validationErrors);
  log->info("written to {}", request.out.string());
  if (outcome->plotError) {
    log->error("{}", outcome->plotError->message);
    return kExitFailure;
  }
  return validationErrors > 0 ? kExitFailure : kExitOk;
}

}  // namespace vegstream::app
