#include "app/streaming_cli.h"

#include <cmath>

#include <CLI/CLI.hpp>

namespace vegstream::app {

void addStreamingOptions(CLI::App& cmd, StreamingCli& o, bool withMode) {
  cmd.add_option("--cpu-budget-mb", o.cpuBudgetMb, "Memory for decoded tiles, MiB (never exceeded)")->capture_default_str();
  cmd.add_option("--gpu-budget-mb", o.gpuBudgetMb, "GPU memory for imagery tiles, MiB (never exceeded)")
      ->capture_default_str();
  cmd.add_option("--upload-mb-per-frame", o.uploadMbPerFrame, "Imagery uploaded to the GPU per frame at most, MiB")
      ->capture_default_str();
  if (withMode)
    cmd.add_option("--streaming", o.mode,
                   "settled: each frame waits for the tiles it wants (the wait is its own column); "
                   "realtime: I/O races the frames as in interactive flight")
        ->check(CLI::IsMember({"settled", "realtime"}))
        ->default_str("settled");
  cmd.add_flag("--no-look-ahead", o.noLookAhead, "Do not prefetch the tiles of the next seconds of the flight");
  cmd.add_option("--terrain-error-px", o.terrainErrorPx, "Screen-space error bound of the terrain, pixels")
      ->capture_default_str();
  cmd.add_option("--terrain-max-nodes", o.terrainMaxNodes, "Most terrain tiles drawn per frame")->capture_default_str();
  cmd.add_option("--terrain-max-triangles", o.terrainMaxTriangles, "Triangle budget of the ROAM terrain mesh")
      ->capture_default_str();
  cmd.add_option("--canopy-m", o.canopyM, "Tallest plant, metres: terrain culling keeps triangles whose plants can be seen")
      ->capture_default_str();
  cmd.add_option("--seed-horizon-m", o.seedHorizonM, "Seed triangles (plants) only within this distance, metres")
      ->capture_default_str();
  cmd.add_option("--http-cache", o.httpCache, "Directory of an on-disk cache for tiles fetched over HTTP");
}

Status applyStreamingOptions(const StreamingCli& o, flight::StreamingMode defaultMode, flight::SceneOptions& scene) {
  auto bad = [](const std::string& m) { return makeError(ErrorKind::InvalidInput, m); };
  auto bytes = [](double mb) { return static_cast<uint64_t>(std::llround(mb * 1024.0 * 1024.0)); };
  if (!(o.cpuBudgetMb >= 1.0 && o.cpuBudgetMb <= 1e6))
    return bad("--cpu-budget-mb " + std::to_string(o.cpuBudgetMb) + ": must be 1 … 1000000 MiB");
  if (!(o.gpuBudgetMb >= 0.25 && o.gpuBudgetMb <= 1e6))
    return bad("--gpu-budget-mb " + std::to_string(o.gpuBudgetMb) + ": must be 0.25 … 1000000 MiB (one imagery tile is 0.25)");
  if (!(o.uploadMbPerFrame >= 0.25 && o.uploadMbPerFrame <= 1e5))
    return bad("--upload-mb-per-frame " + std::to_string(o.uploadMbPerFrame) + ": must be 0.25 … 100000 MiB");
  if (!(o.terrainErrorPx >= 0.1 && o.terrainErrorPx <= 1000.0))
    return bad("--terrain-error-px " + std::to_string(o.terrainErrorPx) + ": must be 0.1 … 1000 pixels");
  if (o.terrainMaxNodes < 1 || o.terrainMaxNodes > 100000)
    return bad("--terrain-max-nodes " + std::to_string(o.terrainMaxNodes) + ": must be 1 … 100000");
  if (o.terrainMaxTriangles < 2 || o.terrainMaxTriangles > 10'000'000)
    return bad("--terrain-max-triangles " + std::to_string(o.terrainMaxTriangles) + ": must be 2 … 10000000");
  if (!(o.canopyM >= 0.0 && o.canopyM <= 200.0))
    return bad("--canopy-m " + std::to_string(o.canopyM) + ": must be 0 … 200 metres");
  if (!(o.seedHorizonM >= 0.0 && o.seedHorizonM <= 20000.0))
    return bad("--seed-horizon-m " + std::to_string(o.seedHorizonM) + ": must be 0 … 20000 metres");
  scene.streaming.cpuBudgetBytes = bytes(o.cpuBudgetMb);
  scene.streaming.gpuBudgetBytes = bytes(o.gpuBudgetMb);
  scene.streaming.uploadBytesPerFrame = bytes(o.uploadMbPerFrame);
  scene.mode = o.mode.empty() ? defaultMode : (o.mode == "settled" ? flight::StreamingMode::Settled
                                                                    : flight::StreamingMode::Realtime);
  scene.lookAhead = !o.noLookAhead;
  scene.terrain.maxErrorPx = o.terrainErrorPx;
  scene.terrain.maxNodes = o.terrainMaxNodes;
  scene.terrain.roam.maxTriangles = static_cast<uint64_t>(o.terrainMaxTriangles);
  scene.terrain.roam.canopyM = o.canopyM;
  scene.terrain.seeds.horizonM = o.seedHorizonM;
  if (!o.httpCache.empty()) scene.httpCacheDir = o.httpCache;
  return {};
}

const char* toString(flight::StreamingMode mode) {
  return mode == flight::StreamingMode::Settled ? "settled" : "realtime";
}

}  // namespace vegstream::app
