// recording.json and summary.json (summary.h).

#include "core/text_file.h"
#include "flight/summary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "flight/frame_columns.h"

namespace vegstream::flight {
namespace fs = std::filesystem;
using nlohmann::json;
namespace col = column;

namespace {

// recording.json's "streaming": the streaming and terrain settings of the run.
json streamingMetaJson(const RecordingMeta::Streaming& s) {
  return json{{"mode", s.mode},
              {"look_ahead", s.lookAhead},
              {"cpu_budget_bytes", s.cpuBudgetBytes},
              {"gpu_budget_bytes", s.gpuBudgetBytes},
              {"upload_bytes_per_frame", s.uploadBytesPerFrame},
              {"max_requests_in_flight", s.maxRequestsInFlight},
              {"imagery_layers", s.imageryLayers},
              {"terrain_error_px", s.terrainErrorPx},
              {"terrain_max_nodes", s.terrainMaxNodes},
              {"terrain_max_triangles", s.terrainMaxTriangles},
              {"canopy_m", s.canopyM},
              {"terrain_detail", s.terrainDetail},
              {"seed_horizon_m", s.seedHorizonM},
              {"seed_level", s.seedLevel},
              {"seed_triangle_area_m2", s.seedTriangleAreaM2}};
}

// recording.json's "plants": the plant settings of the run.
json plantsMetaJson(const RecordingMeta::Plants& p) {
  return json{{"enabled", p.enabled},
              {"density_per_px2", p.density},
              {"max_per_seed_triangle", p.maxPerTriangle},
              {"ground_density_m2", p.groundDensityM2},
              {"fades", p.fades},
              {"cluster_size", p.clusterSize},
              {"species_catalog", p.speciesCatalog},
              {"species", p.species},
              {"style", p.style},
              {"max_segments", p.maxSegments},
              {"lod_distance_m", p.lodDistanceM},
              {"shadows", p.shadows},
              {"shadow_distance_m", p.shadowDistanceM},
              {"occlusion_culling", p.occlusionCulling},
              {"blade_path", p.bladePath},
              {"blade_path_requested", p.bladePathRequested}};
}

}  // namespace

std::string recordingMetaJson(const RecordingMeta& m) {
  const json j = {
      {"device",
       {{"name", m.device.name},
        {"type", m.device.type},
        {"driver", m.device.driver},
        {"api_version", m.device.apiVersion},
        {"software", m.device.software}}},
      {"size", {m.width, m.height}},
      {"msaa", m.msaa},
      {"terrain_shading", m.terrainShading},
      {"fps", m.fps},
      {"warmup_s", m.warmupS},
      {"warmup_frames", m.warmupFrames},
      {"frames_every", m.framesEvery},
      {"frames_in_flight", m.framesInFlight},
      {"path", {{"name", m.pathName}, {"file", m.pathFile}, {"duration_s", m.pathDurationS}}},
      {"dataset",
       {{"name", m.datasetName},
        {"dir", m.datasetDir},
        {"source", m.datasetSource},
        {"height_zoom", m.heightZoom},
        {"imagery_zoom", m.imageryZoom},
        {"ground_zoom", m.groundZoom},
        {"load_ms", m.sceneLoadMs}}},
      {"streaming", streamingMetaJson(m.streaming)},
      {"plants", plantsMetaJson(m.plants)},
      {"datetime", m.sun.datetime},
      {"datetime_source", m.sun.datetimeSource},
      {"sun",
       {{"azimuth_deg", m.sun.azimuthDeg},
        {"elevation_deg", m.sun.elevationDeg},
        {"lat", m.sun.latDeg},
        {"lon", m.sun.lonDeg}}},
      {"exposure_ev", m.exposureEv ? json(*m.exposureEv) : json(nullptr)},
      {"validation", {{"enabled", m.validate}, {"errors", m.validationErrors}, {"warnings", m.validationWarnings}}},
      {"per_pass_gpu_times_meaningful", m.perPassMeaningful},
      {"pipeline_statistics", m.pipelineStatistics},
      {"gpu_passes", m.gpuPasses},
      {"wall_s", m.wallS},
      {"peak_rss_bytes", m.peakRssBytes}};
  return j.dump(2) + "\n";
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double pos = std::clamp(q, 0.0, 100.0) / 100.0 * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (pos - static_cast<double>(lo));
}

std::vector<std::size_t> findHitches(const std::vector<double>& frameMs) {
  std::vector<std::size_t> out;
  std::vector<double> window;
  for (std::size_t i = 1; i < frameMs.size(); ++i) {
    const std::size_t from = i > kHitchWindow ? i - kHitchWindow : 0;
    window.assign(frameMs.begin() + static_cast<std::ptrdiff_t>(from),
                  frameMs.begin() + static_cast<std::ptrdiff_t>(i));
    if (frameMs[i] > kHitchFactor * percentile(window, 50.0)) out.push_back(i);
  }
  return out;
}

namespace {

bool isTimeColumn(const std::string& name) { return name.size() > 3 && name.ends_with("_ms"); }
bool isCountColumn(const std::string& name) {
  return name.starts_with("terrain_") || name.starts_with("stat_") || name.starts_with("plant") ||
         (name.starts_with("stream_") && !isTimeColumn(name));
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}
double maxOf(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// Each frame's cpu_frame_ms + gpu_frame_ms (a missing part counts 0).
std::vector<double> frameTimes(const RecordTable& t) {
  const auto cpu = t.find(col::kCpuFrameMs), gpu = t.find(col::kGpuFrameMs);
  std::vector<double> out(t.rowCount(), 0.0);
  for (std::size_t i = 0; i < t.rowCount(); ++i) {
    if (cpu && !std::isnan(t.at(i, *cpu))) out[i] += t.at(i, *cpu);
    if (gpu && !std::isnan(t.at(i, *gpu))) out[i] += t.at(i, *gpu);
  }
  return out;
}

// A column's values (it is there); an optional column's, or none.
std::vector<double> requiredColumn(const RecordTable& frames, const char* name) {
  return frames.values(*frames.find(name));
}
std::vector<double> optionalColumn(const RecordTable& frames, const char* name) {
  const auto c = frames.find(name);
  return c ? frames.values(*c) : std::vector<double>{};
}

// The percentiles of every time column and the range of every count column.
void summariseColumns(const RecordTable& frames, json& times, json& counts) {
  for (std::size_t c = 0; c < frames.columns().size(); ++c) {
    const std::string& name = frames.columns()[c].name;
    const std::vector<double> v = frames.values(c);
    if (isTimeColumn(name)) {
      times[name] = v.empty() ? json(nullptr)
                              : json{{"p50", percentile(v, 50)},
                                     {"p95", percentile(v, 95)},
                                     {"p99", percentile(v, 99)},
                                     {"max", maxOf(v)},
                                     {"mean", sum(v) / static_cast<double>(v.size())}};
    } else if (isCountColumn(name)) {
      counts[name] = v.empty() ? json(nullptr)
                               : json{{"min", *std::min_element(v.begin(), v.end())},
                                      {"max", maxOf(v)},
                                      {"mean", sum(v) / static_cast<double>(v.size())},
                                      {"total", sum(v)}};
    }
  }
}

// What streaming did over the flight (all zero/empty before issue 5's columns existed).
json streamingTotals(const RecordTable& frames, const std::vector<double>& tS) {
  const auto optional = [&](const char* name) { return optionalColumn(frames, name); };
  const std::vector<double> coarser = optional(col::kMaxLevelsCoarser);
  const std::vector<double> fallback = optional(col::kFallbackPieces);
  std::size_t fallbackFrames = 0, coarseAfter1s = 0;
  for (std::size_t i = 0; i < fallback.size(); ++i) fallbackFrames += fallback[i] > 0.0 ? 1u : 0u;
  for (std::size_t i = 0; i < coarser.size() && i < tS.size(); ++i)
    coarseAfter1s += (tS[i] > 1.0 && coarser[i] > 1.0) ? 1u : 0u;
  json requests = json::object();
  for (const auto& [key, name] :
       {std::pair{"issued", col::kRequestsIssued}, std::pair{"completed", col::kRequestsCompleted},
        std::pair{"cancelled", col::kRequestsCancelled}, std::pair{"failed", col::kRequestsFailed},
        std::pair{"missing", col::kRequestsMissing}, std::pair{"retries", col::kRetries}})
    requests[key] = sum(optional(name));
  return {{"requests", requests},
          {"bytes_read", sum(optional(col::kBytesRead))},
          {"uploads", sum(optional(col::kUploads))},
          {"fallback_frames", fallbackFrames},
          {"frames_more_than_one_level_coarser_after_1s", coarseAfter1s},
          {"max_levels_coarser", maxOf(coarser)},
          {"wait_ms_total", sum(optional(col::kStreamingWaitMs))},
          {"max_bytes_resident_cpu", maxOf(optional(col::kBytesResidentCpu))},
          {"max_bytes_resident_gpu", maxOf(optional(col::kBytesResidentGpu))},
          {"max_error_relaxation", maxOf(optional(col::kErrorRelaxation))}};
}

// The recorder's own time, against the CPU frame's.
json recorderOverhead(const RecordTable& frames) {
  const std::vector<double> cpuFrame = requiredColumn(frames, col::kCpuFrameMs),
                            recorder = requiredColumn(frames, col::kRecorderMs);
  const double meanCpu = cpuFrame.empty() ? 0.0 : sum(cpuFrame) / static_cast<double>(cpuFrame.size());
  const double meanRecorder = recorder.empty() ? 0.0 : sum(recorder) / static_cast<double>(recorder.size());
  double maxShare = 0.0;
  const auto cc = *frames.find(col::kCpuFrameMs), rc = *frames.find(col::kRecorderMs);
  for (std::size_t i = 0; i < frames.rowCount(); ++i)
    if (frames.at(i, cc) > 0.0 && !std::isnan(frames.at(i, rc)))
      maxShare = std::max(maxShare, frames.at(i, rc) / frames.at(i, cc));
  return {{"mean_ms", meanRecorder},
          {"max_ms", maxOf(recorder)},
          {"mean_share_of_cpu_frame", meanCpu > 0.0 ? meanRecorder / meanCpu : 0.0},
          {"max_share_of_cpu_frame", maxShare}};
}

}  // namespace

Result<std::string> makeSummaryJson(const std::string& recordingJson, const std::string& recordingSource,
                                    const RecordTable& frames) {
  json rec = json::parse(recordingJson, nullptr, false);
  if (rec.is_discarded() || !rec.is_object())
    return makeError(ErrorKind::InvalidInput, recordingSource + ": not a JSON object");
  // The recording is copied into the summary and dumped, both recursive in nlohmann: a value
  // nested thousands deep would overflow the stack (found by fuzz/, recording_json).
  constexpr size_t kMaxRecordingDepth = 64;
  if (!jsonDepthAtMost(rec, kMaxRecordingDepth))
    return makeError(ErrorKind::InvalidInput,
                     recordingSource + ": nested deeper than " + std::to_string(kMaxRecordingDepth) + " levels");
  for (const char* name :
       {col::kFrame, col::kTimeS, col::kCpuFrameMs, col::kGpuFrameMs, col::kWallMs, col::kRecorderMs})
    if (!frames.find(name))
      return makeError(ErrorKind::InvalidInput, std::string("frames.csv: missing column ") + name);

  json times = json::object(), counts = json::object();
  summariseColumns(frames, times, counts);
  const std::vector<std::size_t> hitches = findHitches(frameTimes(frames));
  const std::vector<double> tS = requiredColumn(frames, col::kTimeS);
  const double gpuBytesMax = maxOf(optionalColumn(frames, col::kGpuBytes));
  // Not rec.value(key, 0.0): it throws when the key holds another type (a hand-edited file).
  const auto rssField = rec.find("peak_rss_bytes");
  const double rss = rssField != rec.end() && rssField->is_number() ? rssField->get<double>() : 0.0;
  const json summary = {
      {"summary_version", 1},
      {"recording", rec},
      {"frames", frames.rowCount()},
      {"flight_time_s", maxOf(tS)},
      {"times_ms", times},
      {"counts", counts},
      {"hitches",
       {{"count", hitches.size()},
        {"frames", hitches},
        {"factor", kHitchFactor},
        {"window_frames", kHitchWindow},
        {"rule", "cpu_frame_ms + gpu_frame_ms > factor x median of the previous window_frames frames"}}},
      {"peak_memory", {{"rss_hwm_bytes", rss}, {"gpu_bytes", gpuBytesMax}, {"total_bytes", rss + gpuBytesMax}}},
      {"resident_bytes", {{"cpu_max", maxOf(optionalColumn(frames, col::kCpuBytes))}, {"gpu_max", gpuBytesMax}}},
      {"totals",
       {{"wall_s", sum(requiredColumn(frames, col::kWallMs)) / 1000.0},
        {"cpu_frame_ms", sum(requiredColumn(frames, col::kCpuFrameMs))},
        {"gpu_frame_ms", sum(requiredColumn(frames, col::kGpuFrameMs))},
        {"terrain_triangles", sum(optionalColumn(frames, col::kTerrainTriangles))},
        {"png_frames", optionalColumn(frames, col::kPngMs).size()}}},
      {"streaming", streamingTotals(frames, tS)},
      {"recorder_overhead", recorderOverhead(frames)}};
  return summary.dump(2) + "\n";
}

Status writeSummary(const fs::path& dir) {
  auto recText = readTextFile(dir / kRecordingJson, "cannot open (not a recording directory?)");
  if (!recText) return recText.error();
  auto frames = RecordTable::loadCsv(dir / kFramesCsv);
  if (!frames) return frames.error();
  auto text = makeSummaryJson(*recText, (dir / kRecordingJson).string(), *frames);
  if (!text) return text.error();
  return writeTextAtomically(dir / kSummaryJson, *text);
}

}  // namespace vegstream::flight
