// Mutation test of every reader of user JSON (issue 16): the species catalog
// (vegetation/species_catalog.h), dataset.json (datasets/dataset_format.h), flight paths
// (flight/flight_path_json.h), and a recording's recording.json and summary.json
// (flight/summary.h, flight/compare.h) are each fed thousands of seeded, deterministic mutations of a
// small valid file (json_mutations.h: byte flips, truncation, inserted tokens such as 1e9999,
// -1e9990, null, nested arrays, wrong types, deleted and duplicated members), in process. Every
// call must return a value or a user error — never throw, never crash. Then the real executable
// (`vegstream query --species F`) runs on 20 of the catalog mutations that carry a number no
// double holds (the abort of issue 16): exit 0, or 2 with one line on stderr.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_format.h"
#include "flight/compare.h"
#include "flight/flight_path_json.h"
#include "flight/record_table.h"
#include "flight/summary.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/json_mutations.h"
#include "tests/support/run_command.h"
#include "vegetation/species_catalog.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

constexpr uint64_t kSeed = 16;  // issue 16
constexpr int kMutations = 2000;

// Feeds `parse` kMutations mutations of `valid` and checks the tally: no exception, and the
// mutations did their job — most refused, some still read (edits that keep the file valid).
template <typename Parse>
void fuzz(const std::string& valid, const char* reader, Parse&& parse) {
  ASSERT_TRUE(parse(valid).ok()) << reader << ": the unmutated file must read";
  const auto start = std::chrono::steady_clock::now();
  Outcomes tally;
  for (int i = 0; i < kMutations; ++i) {
    const JsonMutation m = mutateJson(valid, kSeed, static_cast<uint64_t>(i));
    expectValueOrError([&] { return parse(m.text); },
                       std::string(reader) + " mutation " + std::to_string(i) + ": " + m.what, tally);
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %d mutations, %d read, %d refused, %d threw, %.0f ms\n", reader, kMutations, tally.ok, tally.refused,
              tally.threw, ms);
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, kMutations / 2) << "most mutations must break the file";
  EXPECT_GT(tally.ok, 0) << "some mutations keep the file valid (a flip inside a string, a duplicate member, …)";
}

TEST(JsonReadersFuzz, SpeciesCatalog) {
  ownTestDir();
  fuzz(std::string(vegetation::defaultSpeciesCatalogJson()), "species catalog",
       [](const std::string& text) { return vegetation::parseSpeciesCatalog(text, "fuzz/species.json"); });
}

TEST(JsonReadersFuzz, DatasetJson) {
  const fs::path dir = ownTestDir();
  datasets::DatasetMeta meta;
  meta.name = "fuzz";
  meta.bounds = {7.9, 46.5, 8.0, 46.6};
  meta.minZoom = 9;
  meta.maxZoom = 13;
  meta.minHeightM = 612.5;
  meta.maxHeightM = 2890.25;
  meta.imagery = datasets::ImageryFormat::Jpeg;
  meta.attribution = "synthetic";
  meta.sources = {{"elevation", "seed 7", "WGS 84 (EPSG:4326)", "fractal relief"},
                  {"imagery", "seed 7", "WGS 84 (EPSG:4326)", "biome colours"}};
  meta.elevationTiles = 40;
  meta.imageryTiles = 40;
  meta.landcover = datasets::LandcoverScheme::Nlcd;  // the optional layer's object is mutated too
  meta.landcoverTiles = 12;
  meta.bytes = 123456;
  ASSERT_TRUE(datasets::writeDatasetMeta(dir, meta).ok());
  const std::string text = readWhole(dir / "dataset.json");
  fuzz(text, "dataset.json", [](const std::string& t) { return datasets::parseDatasetMeta(t, "fuzz/dataset.json"); });
}

TEST(JsonReadersFuzz, FlightPath) {
  ownTestDir();
  const std::string valid = R"({
  "name": "fuzz",
  "description": "three keyframes, a capsule and a wind section",
  "keyframes": [
    {"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 500, "heading": 10, "pitch": -20},
    {"t": 5, "lat": 46.56, "lon": 7.96, "alt_m": 1800, "alt_ref": "msl", "heading": 20, "pitch": -10},
    {"t": 9.5, "lat": 46.57, "lon": 7.97, "alt_m": 30, "alt_ref": "terrain", "heading": 350, "pitch": 0}
  ],
  "colliders": [
    {"name": "log", "shape": "capsule", "radius_m": 0.5, "length_m": 4,
     "keyframes": [{"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 1}, {"t": 9, "lat": 46.551, "lon": 7.951, "alt_m": 1}]}
  ],
  "wind": {"speed_mps": 6, "direction_deg": 250, "gustiness": 0.6,
    "sources": [{"name": "fan", "type": "fan", "radius_m": 8, "strength_mps": 14, "direction_deg": 90,
                 "keyframes": [{"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 3, "alt_ref": "msl"}]}]}
})";
  fuzz(valid, "flight path", [](const std::string& text) { return flight::parseFlightPath(text, "fuzz/path.json"); });
}

// `vegstream report` and `compare` read recording.json and summary.json, files people edit and
// copy around: the same mutations, through makeSummaryJson and compareSummaries.
TEST(JsonReadersFuzz, RecordingAndSummaryJson) {
  ownTestDir();
  auto frames = flight::RecordTable::parseCsv(
      "frame,t_s,cpu_frame_ms,gpu_frame_ms,wall_ms,recorder_ms,terrain_triangles\n"
      "0,0,1.5,2.5,4,0.01,1000\n1,0.016667,1.25,40,42,0.01,1100\n2,0.033333,1.5,2.75,4.5,0.01,900\n",
      "fuzz/frames.csv");
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  const std::string recording = R"({"path": "benchmark-30s", "fps": 60, "size": [640, 360], "msaa": 4,
    "device": {"name": "llvmpipe", "type": "cpu"}, "peak_rss_bytes": 123456789, "per_pass_gpu_times_meaningful": false})";
  fuzz(recording, "recording.json",
       [&](const std::string& text) { return flight::makeSummaryJson(text, "fuzz/recording.json", *frames); });
  const auto summary = flight::makeSummaryJson(recording, "fuzz/recording.json", *frames);
  ASSERT_TRUE(summary.ok());
  fuzz(*summary, "summary.json",
       [&](const std::string& text) { return flight::compareSummaries(text, "fuzz/a/summary.json", *summary, "b"); });
}

// The executable on catalog mutations that hold a number overflow: the abort of issue 16
// (nlohmann's out_of_range.406 escaping) must be one line and exit 2 now; a mutation that still
// reads prints the query's JSON.
TEST(JsonReadersFuzz, QueryWithMutatedSpeciesIsExitZeroOrOneLine) {
  const fs::path dir = ownTestDir();
  const fs::path dataset = dir / "synth";
  const auto g = runVegstream("generate --out '" + dataset.string() + "' --size-km 0.5 --max-zoom 12 --seed 5");
  ASSERT_EQ(g.exitCode, 0) << g.err;
  const std::string valid(vegetation::defaultSpeciesCatalogJson());
  std::vector<std::string> texts = {R"({"species":[{"name":"x","hue": -1e9990}]})"};  // the case of issue 16
  for (uint64_t i = 0; texts.size() < 20; ++i) texts.push_back(mutateJsonWithHugeNumber(valid, kSeed, i).text);
  int refused = 0;
  for (size_t i = 0; i < texts.size(); ++i) {
    const fs::path species = dir / ("species_" + std::to_string(i) + ".json");
    std::ofstream(species, std::ios::binary) << texts[i];
    const auto r =
        runVegstream("query '" + dataset.string() + "' --lat 46.55 --lon 7.95 --species '" + species.string() + "'");
    SCOPED_TRACE(species.string());
    if (r.exitCode == 0) {
      EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;
      EXPECT_TRUE(r.err.empty()) << r.err;
      continue;
    }
    ++refused;
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(species.string()), std::string::npos) << "names the file: " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_GE(refused, 10) << "a number no double holds is refused wherever it stands in a value";
}

}  // namespace
}  // namespace vegstream::testing
