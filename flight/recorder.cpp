// The fixed-step recorder (recorder.h). Per frame it times each CPU stage with a steady clock,
// renders and waits for the frame, and stores the figures in a preallocated plain row; the
// table of named columns is built once at the end, so the per-frame bookkeeping (recorder_ms)
// stays a few hundred nanoseconds.

#include "flight/recorder.h"

#include <array>
#include <optional>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/stopwatch.h"
#include "flight/path_sampler.h"
#include "render/png_writer.h"

namespace vegstream::flight {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxPasses = 16;

// One frame's figures, as measured; NaN = the figure does not exist.
struct FrameRow {
  double t = 0.0;
  FlightSample sample;
  double flightMs = 0.0, streamingMs = 0.0, waitMs = 0.0, terrainMs = 0.0, recordSubmitMs = 0.0;
  SceneFrameFigures scene;
  double gpuFrameMs = 0.0;
  std::array<double, kMaxPasses> passMs{};
  double wallMs = 0.0, recorderMs = 0.0, pngMs = kNoValue;
  double terrainTriangles = 0.0;
  double inputPrimitives = kNoValue, clippingPrimitives = kNoValue, fragmentInvocations = kNoValue;
  std::optional<render::VegetationFigures> vegetation;
  double plantPatches = kNoValue, plantTriangles = kNoValue;  // pipeline statistics of the plant stages
};

double count(uint64_t v) { return static_cast<double>(v); }

void fillTable(RecordTable& table, const std::vector<FrameRow>& rows, const Recording& rec) {
  [[maybe_unused]] const std::size_t passColumn0 = *table.find("gpu_frame_ms") + 1;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const FrameRow& f = rows[i];
    auto& r = table.addRow();
    std::size_t c = 0;
    r[c++] = static_cast<double>(i);
    r[c++] = f.t;
    r[c++] = f.sample.position.latDeg;
    r[c++] = f.sample.position.lonDeg;
    r[c++] = f.sample.position.heightM;
    r[c++] = f.sample.heightAboveGroundM;
    r[c++] = f.sample.headingDeg;
    r[c++] = f.sample.pitchDeg;
    r[c++] = f.flightMs;
    r[c++] = f.streamingMs;
    r[c++] = f.terrainMs;
    r[c++] = f.scene.seedingMs;  // the seed triangles made ready for the classify pass (binning: in record/submit)
    r[c++] = kNoValue;  // cpu_simulation_ms: no simulation yet
    r[c++] = f.recordSubmitMs;
    // cpu_frame_ms: the stages that exist.
    r[c++] = f.flightMs + f.streamingMs + f.terrainMs + f.scene.seedingMs + f.recordSubmitMs;
    r[c++] = f.gpuFrameMs;
    assert(c == passColumn0);
    for (std::size_t p = 0; p < rec.gpuPasses.size(); ++p) r[c++] = rec.perPassMeaningful ? f.passMs[p] : kNoValue;
    r[c++] = f.wallMs;
    r[c++] = f.recorderMs;
    r[c++] = f.pngMs;
    r[c++] = f.terrainTriangles;
    r[c++] = f.inputPrimitives;
    r[c++] = f.clippingPrimitives;
    r[c++] = f.fragmentInvocations;
    r[c++] = count(f.scene.cpuBytes);
    r[c++] = count(f.scene.gpuBytes);
    const streaming::StreamingFrameStats& st = f.scene.streaming;
    const terrain::TerrainFrameFigures& tf = f.scene.terrain;
    r[c++] = f.waitMs;
    r[c++] = st.longestWaitS * 1000.0;
    for (uint64_t v : {st.requestsIssued, st.requestsCompleted, st.requestsCancelled, st.requestsFailed,
                       st.requestsMissing, st.retries, st.bytesRead, f.scene.uploads, st.uploadBytes, st.evictionsCpu,
                       st.evictionsGpu, st.tilesResidentCpu, st.tilesResidentGpu, st.bytesResidentCpu,
                       st.bytesResidentGpu, st.requestsInFlight, st.wanted, st.wantedResident, tf.lookAheadWants,
                       tf.pieces, tf.fallbackPieces, static_cast<uint64_t>(tf.maxLevelsCoarser), tf.meshesBuilt})
      r[c++] = count(v);
    r[c++] = tf.errorBoundPx;
    r[c++] = tf.relaxation;
    // Issue 6: ROAM and seed triangles (sub-stages of cpu_terrain_ms, not added to cpu_frame_ms).
    r[c++] = tf.roam.updateMs;
    r[c++] = tf.roam.outputMs;
    for (uint64_t v : {tf.roam.leaves, tf.roam.splits, tf.roam.merges, tf.roam.constrainedLeaves,
                       static_cast<uint64_t>(tf.roam.budgetLimited), static_cast<uint64_t>(tf.roam.workLimited),
                       tf.roam.seedTriangles, tf.roam.seedInterpolated, tf.roam.depthLimitedLeaves})
      r[c++] = count(v);
    r[c++] = tf.roam.seedPlants;
    r[c++] = tf.roam.achievedErrorPx;
    // Issue 7: the classify pass (render/classify_pass.h); NaN when plants are off.
    const auto& v = f.vegetation;
    for (uint64_t x : {uint64_t{v ? v->seedTriangles : 0u}, uint64_t{v ? v->bins : 0u}, v ? v->clusters : 0,
                       v ? v->clusterSlots : 0, v ? v->groupsTotal : 0, v ? v->plantsTotal : 0,
                       uint64_t{v && v->overflow}})
      r[c++] = v ? count(x) : kNoValue;
    r[c++] = f.plantPatches;
    r[c++] = f.plantTriangles;
    assert(c == r.size());
  }
}

}  // namespace

std::size_t frameCount(double durationS, double fps) {
  assert(fps > 0.0 && durationS >= 0.0);
  return static_cast<std::size_t>(std::floor(durationS * fps + 1e-9)) + 1;
}

std::string gpuPassColumn(const std::string& pass) {
  std::string out = "gpu_";
  for (char ch : pass) {
    const char c = (ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch;
    out += ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) ? c : '_';
  }
  return out + "_ms";
}

std::vector<RecordColumn> frameColumns(const std::vector<std::string>& gpuPasses) {
  std::vector<RecordColumn> c = {
      {"frame", 0},          {"t_s", 6},        {"lat", 9},        {"lon", 9},
      {"alt_msl_m", 3},      {"height_above_ground_m", 3},         {"heading_deg", 4},
      {"pitch_deg", 4},      {"cpu_flight_ms", 6},                 {"cpu_streaming_ms", 6},
      {"cpu_terrain_ms", 6}, {"cpu_seeding_ms", 6},                {"cpu_simulation_ms", 6},
      {"cpu_record_submit_ms", 6},              {"cpu_frame_ms", 6}, {"gpu_frame_ms", 4}};
  for (const auto& p : gpuPasses) c.push_back({gpuPassColumn(p), 4});
  c.push_back({"wall_ms", 4});
  c.push_back({"recorder_ms", 6});  // sub-microsecond: nanosecond digits
  c.push_back({"png_ms", 4});
  for (const char* n : {"terrain_triangles", "stat_input_primitives", "stat_clipping_primitives",
                        "stat_fragment_invocations", "cpu_bytes", "gpu_bytes"})
    c.push_back({n, 0});
  c.push_back({"streaming_wait_ms", 4});       // settled mode's wait, left out of the frame time
  c.push_back({"stream_longest_wait_ms", 1});  // oldest wanted tile not resident yet
  for (const char* n : {"stream_requests_issued", "stream_requests_completed", "stream_requests_cancelled",
                        "stream_requests_failed", "stream_requests_missing", "stream_retries", "stream_bytes_read",
                        "stream_uploads", "stream_upload_bytes", "stream_evictions_cpu", "stream_evictions_gpu",
                        "stream_tiles_resident_cpu", "stream_tiles_resident_gpu", "stream_bytes_resident_cpu",
                        "stream_bytes_resident_gpu", "stream_requests_in_flight", "stream_wanted",
                        "stream_wanted_resident", "stream_lookahead_wants", "terrain_pieces",
                        "terrain_fallback_pieces", "terrain_max_levels_coarser", "terrain_meshes_built"})
    c.push_back({n, 0});
  c.push_back({"terrain_error_bound_px", 3});
  c.push_back({"terrain_error_relaxation", 3});
  c.push_back({"terrain_roam_update_ms", 6});
  c.push_back({"terrain_roam_output_ms", 6});
  for (const char* n : {"terrain_leaves", "terrain_splits", "terrain_merges", "terrain_constrained_leaves",
                        "terrain_triangle_budget_hit", "terrain_work_budget_hit", "terrain_seed_triangles",
                        "terrain_seed_interpolated", "terrain_depth_limited_leaves"})
    c.push_back({n, 0});
  c.push_back({"terrain_seed_plants", 1});
  c.push_back({"terrain_achieved_error_px", 3});
  for (const char* n : {"plant_seed_triangles", "plant_bins", "plant_clusters", "plant_cluster_slots", "plant_groups",
                        "plants", "plant_overflow", "plant_patches", "plant_triangles"})
    c.push_back({n, 0});
  return c;
}

uint64_t peakResidentBytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    unsigned long long kb = 0;
    if (std::sscanf(line.c_str(), "VmHWM: %llu kB", &kb) == 1) return static_cast<uint64_t>(kb) * 1024u;
  }
  return 0;
}

Result<Recording> recordFlight(Scene& scene, const FlightPath& path, const RecorderOptions& options) {
  assert(options.fps > 0.0 && options.warmupS >= 0.0 && options.framesEvery >= 0);
  render::Renderer& renderer = scene.renderer();
  const PathSampler sampler(path);
  const GroundHeight ground = scene.groundFunction();
  const std::size_t n = frameCount(sampler.duration(), options.fps);

  Recording rec;
  rec.warmupFrames = static_cast<std::size_t>(std::llround(options.warmupS * options.fps));
  Stopwatch total;
  if (rec.warmupFrames > 0) {
    const FlightSample start = sampler.sample(0.0, ground);
    const std::vector<FlightSample> ahead = lookAheadSamples(sampler, ground, 0.0);
    for (std::size_t i = 0; i < rec.warmupFrames; ++i)
      if (auto f = renderer.renderFrame(scene.prepareFrame(start, 0.0, ahead)); !f) return f.error();
  }

  std::vector<FrameRow> rows;
  rows.reserve(n);
  bool first = true;
  for (std::size_t i = 0; i < n; ++i) {
    Stopwatch frameWatch;
    const double t = std::min(static_cast<double>(i) / options.fps, sampler.duration());
    const bool savePng = options.framesEvery > 0 && i % static_cast<std::size_t>(options.framesEvery) == 0;

    Stopwatch stage;
    const FlightSample sample = sampler.sample(t, ground);
    const double flightMs = stage.elapsedMs();
    const std::vector<FlightSample> ahead = lookAheadSamples(sampler, ground, t);
    const double flightAheadMs = stage.elapsedMs() - flightMs;
    render::FrameRequest request = scene.prepareFrame(sample, t, ahead);
    const SceneFrameFigures& figures = scene.lastFrameFigures();
    request.readbackColor = savePng;
    auto result = renderer.renderFrame(request);
    if (!result) return result.error();

    Stopwatch bookkeeping;
    const render::GpuTimings& gpu = result->gpu;
    if (first) {
      first = false;
      rec.perPassMeaningful = gpu.perPassMeaningful;
      rec.pipelineStatistics = gpu.statistics.available;
      for (std::size_t p = 0; p < gpu.passes.size() && p < kMaxPasses; ++p) rec.gpuPasses.push_back(gpu.passes[p].pass);
    }
    FrameRow& row = rows.emplace_back();
    row.t = t;
    row.sample = sample;
    row.flightMs = flightMs + flightAheadMs;
    row.streamingMs = figures.streamingMs;
    row.waitMs = figures.settleWaitMs;
    row.terrainMs = figures.terrainMs;
    row.scene = figures;
    row.recordSubmitMs = result->cpuRecordMs;
    row.gpuFrameMs = gpu.frameMs;
    for (std::size_t p = 0; p < rec.gpuPasses.size(); ++p)
      row.passMs[p] = p < gpu.passes.size() && gpu.passes[p].pass == rec.gpuPasses[p] ? gpu.passes[p].ms : kNoValue;
    row.terrainTriangles = count(result->terrainTriangles);
    row.vegetation = result->vegetation;
    if (gpu.statistics.available) {
      row.inputPrimitives = count(gpu.statistics.inputPrimitives);
      row.clippingPrimitives = count(gpu.statistics.clippingPrimitives);
      row.fragmentInvocations = count(gpu.statistics.fragmentInvocations);
      // Only the plant pipelines tessellate and run geometry shaders: their figures are these.
      if (result->vegetation) {
        row.plantPatches = count(gpu.statistics.tessControlPatches);
        row.plantTriangles = count(gpu.statistics.geometryPrimitives);
      }
    }
    row.recorderMs = bookkeeping.elapsedMs();
    row.wallMs = frameWatch.elapsedMs() - figures.settleWaitMs;

    if (savePng) {
      Stopwatch png;
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05zu.png", i);
      assert(result->color && "the renderer returns the colour read-back it was asked for");
      if (Status s = render::writePng(options.framesDir / name, *result->color); !s) return s.error();
      row.pngMs = png.elapsedMs();
      ++rec.pngFrames;
    }
    if (options.progress) options.progress(i + 1, n);
  }

  rec.table = RecordTable(frameColumns(rec.gpuPasses));
  fillTable(rec.table, rows, rec);
  rec.wallS = total.elapsedMs() / 1000.0;
  rec.peakRssBytes = peakResidentBytes();
  return rec;
}

}  // namespace vegstream::flight
