// The frame-time plot's stacked series (flight/plots/recording_plots.py, issue 19): the shared
// simulation is its own band — cpu_simulation_ms among the CPU stages, gpu_simulation_ms among
// the GPU passes where per-pass times exist — and disappears where its column is empty. Runs the
// embedded script (`series DIR` lists what frame_time.png stacks; `report DIR` draws it) on a
// frames.csv with the recorder's columns it reads.

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "flight/frame_columns.h"
#include "flight/record_table.h"
#include "flight/report.h"
#include "tests/support/test_dirs.h"

namespace vegstream::flight {
namespace {
namespace fs = std::filesystem;

// The renderer's passes with the simulation's (render/frame_passes.cpp names it "simulation").
const std::vector<std::string> kPasses = {"simulation", "terrain", "terrain_shade", "classify", "blades", "plants"};

// A recording of 30 frames; `perPass`: per-pass GPU times exist (not a CPU rasteriser);
// `simulating`: cpu_simulation_ms is filled (the simulation is on).
fs::path writeRecording(const fs::path& dir, bool perPass, bool simulating) {
  // The recorder's columns the plot reads, in file order (scene/frame_figures.h declares them all).
  std::vector<RecordColumn> columns;
  for (const char* name :
       {"frame", "t_s", "height_above_ground_m", "cpu_flight_ms", "cpu_streaming_ms", "cpu_terrain_ms",
        "cpu_seeding_ms", "cpu_simulation_ms", "cpu_record_submit_ms", "cpu_frame_ms", "gpu_frame_ms"})
    columns.push_back({name, 6});
  for (const std::string& p : kPasses) columns.push_back({column::gpuPassColumn(p), 4});
  columns.push_back({"wall_ms", 4});
  RecordTable t(columns);
  for (int i = 0; i < 30; ++i) {
    std::vector<double>& r = t.addRow();
    auto set = [&](const std::string& name, double v) { r[*t.find(name)] = v; };
    set("frame", i);
    set("t_s", i / 30.0);
    set("height_above_ground_m", 100.0);
    for (const char* stage :
         {"cpu_flight_ms", "cpu_streaming_ms", "cpu_terrain_ms", "cpu_seeding_ms", "cpu_record_submit_ms"})
      set(stage, 0.5);
    if (simulating) set("cpu_simulation_ms", 0.25);
    set("cpu_frame_ms", simulating ? 2.75 : 2.5);
    set("gpu_frame_ms", 6.0);
    if (perPass)
      for (const std::string& p : kPasses) set(column::gpuPassColumn(p), 1.0);
    set("wall_ms", 16.7);
  }
  std::ofstream(dir / "frames.csv") << t.toCsv();
  std::ofstream(dir / "summary.json") << "{}";
  return dir;
}

struct ScriptRun {
  int exitCode = -1;
  std::string out;
};

// `python SCRIPT args…` with the first interpreter of defaultPythons() that has matplotlib
// (exit 3: it has none; 127: no such interpreter), as `vegstream report` picks it.
ScriptRun runScript(const fs::path& dir, const std::string& args) {
  const fs::path script = dir / "recording_plots.py";
  std::ofstream(script) << plotScriptText();
  ScriptRun run;
  for (const std::string& python : defaultPythons()) {
    const std::string command = "'" + python + "' '" + script.string() + "' " + args + " 2>/dev/null";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) continue;
    run.out.clear();
    char buf[4096];
    while (std::fgets(buf, sizeof(buf), pipe) != nullptr) run.out += buf;
    const int status = ::pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    if (run.exitCode != 3 && run.exitCode != 127) return run;
  }
  return run;
}

// "panel\tcolumn" of every series, in order.
std::vector<std::string> seriesOf(const fs::path& dir) {
  const ScriptRun run = runScript(dir, "series '" + dir.string() + "'");
  EXPECT_EQ(run.exitCode, 0) << "no interpreter with matplotlib among defaultPythons()";
  std::vector<std::string> series;
  std::size_t start = 0;
  while (start < run.out.size()) {
    const std::size_t end = run.out.find('\n', start);
    const std::string line = run.out.substr(start, end - start);
    series.push_back(line.substr(0, line.rfind('\t')));  // without the legend text
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return series;
}

TEST(RecordingPlots, FrameTimeStacksTheSimulationOnCpuAndGpu) {
  const fs::path dir = writeRecording(testing::testOutputDir(), true, true);
  const std::vector<std::string> expected = {
      "gpu\tgpu_frame_ms",  // the frame less the named passes
      "gpu\tgpu_simulation_ms", "gpu\tgpu_classify_ms+gpu_blades_ms+gpu_plants_ms",
      "cpu\tcpu_flight_ms",     "cpu\tcpu_streaming_ms",
      "cpu\tcpu_terrain_ms",    "cpu\tcpu_seeding_ms",
      "cpu\tcpu_simulation_ms", "cpu\tcpu_record_submit_ms",
  };
  EXPECT_EQ(seriesOf(dir), expected);
  // Its legend names it.
  const ScriptRun run = runScript(dir, "series '" + dir.string() + "'");
  EXPECT_NE(run.out.find("gpu\tgpu_simulation_ms\tsimulation pass"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("cpu\tcpu_simulation_ms\tsimulation"), std::string::npos) << run.out;
}

TEST(RecordingPlots, CpuRasteriserHasNoGpuSimulationBandButTheCpuStage) {
  // lavapipe: every gpu_<pass>_ms empty, so the GPU frame is one band.
  const fs::path dir = writeRecording(testing::testOutputDir(), false, true);
  const std::vector<std::string> series = seriesOf(dir);
  ASSERT_FALSE(series.empty());
  EXPECT_EQ(series.front(), "gpu\tgpu_frame_ms");
  EXPECT_EQ(std::count(series.begin(), series.end(), "gpu\tgpu_simulation_ms"), 0);
  EXPECT_EQ(std::count(series.begin(), series.end(), "cpu\tcpu_simulation_ms"), 1);
}

TEST(RecordingPlots, SimulationOffLeavesItsCpuStageOut) {
  const fs::path dir = writeRecording(testing::testOutputDir(), true, false);
  const std::vector<std::string> series = seriesOf(dir);
  EXPECT_EQ(std::count(series.begin(), series.end(), "cpu\tcpu_simulation_ms"), 0);
  EXPECT_EQ(std::count(series.begin(), series.end(), "cpu\tcpu_terrain_ms"), 1);
}

TEST(RecordingPlots, ReportDrawsTheFrameTimePlotWithTheSimulation) {
  for (const bool perPass : {true, false}) {
    const fs::path dir = testing::testOutputDir() / (perPass ? "per_pass" : "cpu_rasteriser");
    fs::create_directories(dir);
    writeRecording(dir, perPass, true);
    ASSERT_TRUE(makePlots(dir, defaultPythons())) << dir;
    for (const std::string& name : reportPlotNames()) EXPECT_GT(fs::file_size(dir / name), 1000u) << name;
  }
}

}  // namespace
}  // namespace vegstream::flight
