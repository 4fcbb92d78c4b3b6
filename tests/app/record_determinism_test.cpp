// `vegstream record` is repeatable (DESIGN.md: "the same inputs give the same counts and, on
// the same driver, the same images"): the real executable records the benchmark-30s flight over
// the imported Zion sample twice — settled streaming with look-ahead, whose prefetched tiles
// used to land at whatever frame their I/O finished — and every count column of frames.csv
// (all but the `*_ms` timings) and every saved PNG must be equal, byte for byte. The same
// flight served by nginx on loopback must give what the directory gives. Keeping one frame in
// flight (--frames-in-flight 1, the serial playback) with the terrain copied every frame must
// give what three frames in flight with the terrain resident give.
//
// Each test works in its own directory, <VEGSTREAM_TEST_TMP>/<suite>.<test>/, so the suite can
// run in parallel. The Zion sample (tests/support/zion_sample.h) and the default recording that
// each test holds its own against are made once, by whichever test process comes first
// (cachedFixture), and only read after.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/nginx_server.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;
using testing::runVegstream;

fs::path testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(VEGSTREAM_TEST_TMP) / (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The repository's benchmark flight (this file is tests/app/…; __FILE__ is relative to the build
// directory, the parent of the executable's app/, when the compiler was given a relative path).
fs::path benchmarkPath() {
  fs::path self(__FILE__);
  if (self.is_relative()) self = fs::path(VEGSTREAM_EXE).parent_path().parent_path() / self;
  const fs::path path = self.parent_path().parent_path().parent_path() / "flight" / "paths" / "benchmark-30s.json";
  EXPECT_TRUE(fs::exists(path)) << path;
  return path.lexically_normal();
}

constexpr int kFramesEvery = 10;

// benchmark-30s at 160x90, 4 fps (121 frames), every 10th frame saved; `extra`: more options.
testing::CommandResult recordCommand(const std::string& dataset, const fs::path& out, const std::string& extra = "") {
  return runVegstream("record '" + dataset + "' --path '" + benchmarkPath().string() + "' --out '" + out.string() +
                      "' --size 160x90 --msaa 1 --fps 4 --frames-every " + std::to_string(kFramesEvery) +
                      " --no-plots" + extra);
}
void record(const std::string& dataset, const fs::path& out, const std::string& extra = "") {
  const auto r = recordCommand(dataset, out, extra);
  ASSERT_EQ(r.exitCode, 0) << r.err;
}

// The imported sample and its default recording (settled, look-ahead, three frames in flight):
// what every test compares its own recording with.
struct Reference {
  fs::path dataset, recording;
};
Reference reference() {
  auto zion = testing::zionSampleDataset();
  EXPECT_TRUE(zion.ok()) << zion.error().message;
  if (!zion.ok()) return {};
  auto rec =
      testing::cachedFixture("benchmark-30s-recording", testing::vegstreamKey(), [&](const fs::path& dir) -> Status {
        const auto r = recordCommand(zion->string(), dir);
        if (r.exitCode == 0) return {};
        return makeError(ErrorKind::Internal, "vegstream record: " + r.err);
      });
  EXPECT_TRUE(rec.ok()) << rec.error().message;
  return {*zion, rec.ok() ? *rec : fs::path()};
}

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> column(const std::string& name) const {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name;
    std::vector<std::string> out;
    if (at == header.end()) return out;
    const auto i = static_cast<size_t>(at - header.begin());
    for (const auto& r : rows) out.push_back(i < r.size() ? r[i] : "");
    return out;
  }
};

std::vector<std::string> splitCsvLine(const std::string& line) {  // frames.csv has no quoted fields
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

Table readFrames(const fs::path& recording) {
  Table t;
  std::ifstream f(recording / "frames.csv");
  std::string line;
  if (std::getline(f, line)) t.header = splitCsvLine(line);
  while (std::getline(f, line))
    if (!line.empty()) t.rows.push_back(splitCsvLine(line));
  return t;
}

bool isTiming(const std::string& column) { return column.size() > 3 && column.ends_with("_ms"); }

// Every column but the timings (and `ignore`), cell by cell; the first few differences are named.
void expectSameCounts(const fs::path& a, const fs::path& b, const std::vector<std::string>& ignore = {}) {
  const Table ta = readFrames(a), tb = readFrames(b);
  ASSERT_EQ(ta.header, tb.header);
  ASSERT_EQ(ta.rows.size(), 121u) << "benchmark-30s at 4 fps";
  ASSERT_EQ(tb.rows.size(), ta.rows.size());
  int compared = 0, differing = 0;
  for (const std::string& name : ta.header) {
    if (isTiming(name) || std::find(ignore.begin(), ignore.end(), name) != ignore.end()) continue;
    ++compared;
    const auto ca = ta.column(name), cb = tb.column(name);
    for (size_t i = 0; i < ca.size(); ++i) {
      if (ca[i] == cb[i]) continue;
      if (++differing <= 10) ADD_FAILURE() << name << " differs at frame " << i << ": " << ca[i] << " vs " << cb[i];
    }
  }
  EXPECT_EQ(differing, 0) << "cells that differ";
  EXPECT_GT(compared, 40) << "count columns compared";
  // What the comparison covers: the terrain's counts, and a flight that prefetches ahead.
  for (const char* name : {"terrain_triangles", "terrain_splits", "stream_requests_completed", "plants"})
    EXPECT_NE(std::find(ta.header.begin(), ta.header.end(), name), ta.header.end()) << name;
  const auto ahead = ta.column("stream_lookahead_wants");
  EXPECT_TRUE(std::any_of(ahead.begin(), ahead.end(), [](const std::string& v) { return !v.empty() && v != "0"; }))
      << "the flight wants look-ahead tiles";
}

std::string readBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The same frame files with the same bytes.
void expectSameFrames(const fs::path& a, const fs::path& b) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(a / "frames")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  ASSERT_EQ(names.size(), 26u) << "frames 0, 10, …, 120, each PNG with its sidecar JSON";
  for (const std::string& n : names) {
    const std::string pa = readBytes(a / "frames" / n), pb = readBytes(b / "frames" / n);
    EXPECT_GT(pa.size(), 100u) << n;
    EXPECT_TRUE(pa == pb) << n << " differs (" << pa.size() << " vs " << pb.size() << " bytes)";
  }
}

TEST(RecordDeterminism, TwoRecordingsOfBenchmark30sHaveTheSameCountsAndFrames) {
  const fs::path dir = testDir();
  const Reference ref = reference();
  ASSERT_TRUE(fs::exists(ref.recording / "frames.csv"));
  record(ref.dataset.string(), dir / "second");
  expectSameCounts(ref.recording, dir / "second");
  expectSameFrames(ref.recording, dir / "second");
}

double sum(const std::vector<std::string>& column) {
  double total = 0.0;
  for (const std::string& v : column) total += v.empty() ? 0.0 : std::stod(v);
  return total;
}
// Two ways of playing the flight that must draw what the default draws, byte for byte, in one
// recording (each recording of benchmark-30s costs a minute of the CI's two cores; the two are
// independent, and a difference from either would show as a difference here):
//   - one frame in flight (--frames-in-flight 1, the serial playback) against three;
//   - the terrain's vertices copied every frame (--terrain-geometry copied) against resident on
//     the GPU (the default; render/terrain_geometry_buffers.h), which uploads only the chunks
//     that are new or moved (issue 44 item 2).
TEST(RecordDeterminism, SerialPlaybackWithCopiedTerrainDrawsWhatTheDefaultDraws) {
  const fs::path dir = testDir();
  const Reference ref = reference();
  ASSERT_TRUE(fs::exists(ref.recording / "frames.csv"));
  record(ref.dataset.string(), dir / "other", " --frames-in-flight 1 --terrain-geometry copied");
  const std::vector<std::string> geometry = {"terrain_chunks", "terrain_chunks_uploaded", "terrain_vertices_uploaded"};
  std::vector<std::string> ignore = geometry;
  ignore.push_back("gpu_bytes");  // the pool and the slots' buffers are not the same sizes
  expectSameCounts(ref.recording, dir / "other", ignore);
  expectSameFrames(ref.recording, dir / "other");
  // recording.json says how each was played (its wall times depend on it).
  EXPECT_NE(readBytes(dir / "other" / "recording.json").find("\"frames_in_flight\": 1"), std::string::npos);
  EXPECT_NE(readBytes(ref.recording / "recording.json").find("\"frames_in_flight\": 3"), std::string::npos);
  const Table copied = readFrames(dir / "other"), resident = readFrames(ref.recording);
  for (const std::string& name : geometry) EXPECT_EQ(sum(copied.column(name)), 0.0) << name << " when copied";
  // Resident: the first frame uploads every chunk it draws; over the flight, most draws reuse one.
  const auto drawn = resident.column("terrain_chunks"), uploaded = resident.column("terrain_chunks_uploaded");
  ASSERT_FALSE(drawn.empty());
  EXPECT_GT(std::stod(drawn[0]), 0.0);
  EXPECT_EQ(drawn[0], uploaded[0]);
  EXPECT_GT(sum(drawn), 20000.0) << "chunks drawn over the flight";
  EXPECT_LT(sum(uploaded), 0.5 * sum(drawn)) << "chunks uploaded over the flight";
}

TEST(RecordDeterminism, ARecordingOverNginxEqualsOneFromTheDirectory) {
  const fs::path dir = testDir();
  const Reference ref = reference();
  ASSERT_TRUE(fs::exists(ref.recording / "frames.csv"));
  auto nginx = testing::NginxServer::start(ref.dataset, dir / "nginx");
  ASSERT_TRUE(nginx.ok()) << nginx.error().message;
  record((*nginx)->baseUrl(), dir / "http");
  EXPECT_GT((*nginx)->accessLog().size(), 50u) << "the tiles really came over HTTP";
  expectSameCounts(ref.recording, dir / "http");
  expectSameFrames(ref.recording, dir / "http");
}

}  // namespace
}  // namespace vegstream
