// The JSON readers: dataset.json (datasets/dataset_format.h), flight paths
// (flight/flight_path_json.h), the species catalog (vegetation/species_catalog.h), and a
// recording's recording.json and summary.json (flight/summary.h, flight/compare.h). Any text,
// nested or large however it is: a value or an error with a message, never an exception or a
// crash (a deep nesting must not overflow the stack of a recursive walk).

#include <cmath>
#include <string>

#include "datasets/dataset_format.h"
#include "flight/compare.h"
#include "flight/flight_path_json.h"
#include "flight/record_table.h"
#include "flight/summary.h"
#include "fuzz/targets.h"
#include "vegetation/species_catalog.h"

namespace vegstream::fuzz {
namespace {

const flight::RecordTable& frames() {
  static const flight::RecordTable table = [] {
    auto t = flight::RecordTable::parseCsv(
        "frame,t_s,cpu_frame_ms,gpu_frame_ms,wall_ms,recorder_ms,terrain_triangles\n"
        "0,0,1.5,2.5,4,0.01,1000\n1,0.016667,1.25,40,42,0.01,1100\n2,0.033333,1.5,2.75,4.5,0.01,900\n",
        "fuzz/frames.csv");
    if (!t) fail("the fixed frames.csv must parse", __FILE__, __LINE__);
    return std::move(*t);
  }();
  return table;
}

const std::string& validSummary() {
  static const std::string s = [] {
    auto r = flight::makeSummaryJson(
        R"({"path": "benchmark-30s", "fps": 60, "size": [640, 360], "msaa": 4,
            "device": {"name": "llvmpipe", "type": "cpu"}, "peak_rss_bytes": 123456789,
            "per_pass_gpu_times_meaningful": false})",
        "fuzz/recording.json", frames());
    if (!r) fail("the fixed recording.json must summarise", __FILE__, __LINE__);
    return *r;
  }();
  return s;
}

}  // namespace

int datasetJson(const uint8_t* data, size_t size) {
  const auto r = datasets::parseDatasetMeta(asText(data, size), "fuzz/dataset.json");
  checkResult(r);
  if (r) {
    // What the readers of a dataset rely on once dataset.json has read.
    VEGSTREAM_FUZZ_CHECK(r->tileSize >= 1 && r->tileSize <= 4096);
    VEGSTREAM_FUZZ_CHECK(r->minZoom <= r->maxZoom);
  }
  return 0;
}

int flightPath(const uint8_t* data, size_t size) {
  const auto r = flight::parseFlightPath(asText(data, size), "fuzz/path.json");
  checkResult(r);
  return 0;
}

int speciesCatalog(const uint8_t* data, size_t size) {
  const auto r = vegetation::parseSpeciesCatalog(asText(data, size), "fuzz/species.json");
  checkResult(r);
  return 0;
}

int recordingJson(const uint8_t* data, size_t size) {
  const auto r = flight::makeSummaryJson(asText(data, size), "fuzz/recording.json", frames());
  checkResult(r);
  if (r) {
    // The summary written from a recording that read must itself read back.
    const auto back = flight::compareSummaries(*r, "fuzz/summary.json", validSummary(), "b");
    checkResult(back);
    VEGSTREAM_FUZZ_CHECK(back.ok());
  }
  return 0;
}

int summaryJson(const uint8_t* data, size_t size) {
  const std::string text = asText(data, size);
  const auto ab = flight::compareSummaries(text, "fuzz/a/summary.json", validSummary(), "fuzz/b/summary.json");
  checkResult(ab);
  const auto ba = flight::compareSummaries(validSummary(), "fuzz/a/summary.json", text, "fuzz/b/summary.json");
  checkResult(ba);
  VEGSTREAM_FUZZ_CHECK(ab.ok() == ba.ok());
  if (ab) {
    for (const auto& row : *ab) (void)flight::ratio(row);
  }
  return 0;
}

}  // namespace vegstream::fuzz
