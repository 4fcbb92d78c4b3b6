// Side-by-side summaries (compare.h).

#include "core/text_file.h"
#include "flight/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "flight/summary.h"

namespace vegstream::flight {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Flattens the comparable numbers into (key, value) in a stable order.
std::vector<std::pair<std::string, double>> flatten(const json& s) {
  std::vector<std::pair<std::string, double>> out;
  auto num = [](const json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
  auto add = [&](const std::string& key, const json& v) { out.emplace_back(key, num(v)); };
  add("frames", s.value("frames", json()));
  add("flight_time_s", s.value("flight_time_s", json()));
  if (s.contains("times_ms") && s["times_ms"].is_object())
    for (const auto& [col, st] : s["times_ms"].items())
      for (const char* q : {"p50", "p95", "p99", "max"})
        add("times_ms." + col + "." + q, st.is_object() ? st.value(q, json()) : json());
  if (s.contains("counts") && s["counts"].is_object())
    for (const auto& [col, st] : s["counts"].items())
      add("counts." + col + ".mean", st.is_object() ? st.value("mean", json()) : json());
  // Numbers of the groups, one level of nesting flattened (streaming.requests.issued).
  for (const char* group : {"hitches", "peak_memory", "resident_bytes", "totals", "streaming", "recorder_overhead"}) {
    if (!s.contains(group) || !s[group].is_object()) continue;
    for (const auto& [k, v] : s[group].items()) {
      if (v.is_number()) add(std::string(group) + "." + k, v);
      if (v.is_object())
        for (const auto& [k2, v2] : v.items())
          if (v2.is_number()) add(std::string(group) + "." + k + "." + k2, v2);
    }
  }
  return out;
}

Result<json> parseSummary(const std::string& text, const std::string& source) {
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("summary_version"))
    return makeError(ErrorKind::InvalidInput,
                     source + ": not a vegstream summary.json (run `vegstream report` on its directory)");
  return j;
}

std::string cell(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

}  // namespace

Result<std::vector<CompareRow>> compareSummaries(const std::string& summaryA, const std::string& sourceA,
                                                 const std::string& summaryB, const std::string& sourceB) {
  auto a = parseSummary(summaryA, sourceA);
  if (!a) return a.error();
  auto b = parseSummary(summaryB, sourceB);
  if (!b) return b.error();
  const auto fa = flatten(*a), fb = flatten(*b);
  std::vector<CompareRow> rows;
  // Each key's first row, so that B's keys are matched in constant time: a linear search per key
  // made two summaries of n keys cost n² (a 20 KB summary.json with 2 300 "times_ms" columns
  // took seconds; found profiling the summary_json fuzz target). A key that appears twice (a
  // dotted key and a nested one can flatten alike) still matches its first row, as the search did.
  std::unordered_map<std::string, std::size_t> firstRow;
  for (const auto& [k, v] : fa) {
    firstRow.emplace(k, rows.size());
    rows.push_back({k, v, std::nan("")});
  }
  for (const auto& [k, v] : fb) {
    if (const auto it = firstRow.find(k); it != firstRow.end()) {
      rows[it->second].b = v;
    } else {
      firstRow.emplace(k, rows.size());
      rows.push_back({k, std::nan(""), v});
    }
  }
  return rows;
}

Result<std::vector<CompareRow>> compareRecordings(const fs::path& dirA, const fs::path& dirB) {
  auto a = readTextFile(dirA / kSummaryJson, "cannot open (not a recording directory?)");
  if (!a) return a.error();
  auto b = readTextFile(dirB / kSummaryJson, "cannot open (not a recording directory?)");
  if (!b) return b.error();
  return compareSummaries(*a, (dirA / kSummaryJson).string(), *b, (dirB / kSummaryJson).string());
}

double ratio(const CompareRow& row) {
  if (std::isnan(row.a) || std::isnan(row.b) || row.a == 0.0) return std::nan("");
  return row.b / row.a;
}

std::string formatCompareTable(const std::vector<CompareRow>& rows, const std::string& nameA,
                               const std::string& nameB) {
  std::size_t width = 3;
  for (const auto& r : rows) width = std::max(width, r.key.size());
  std::string out = "A: " + nameA + "\nB: " + nameB + "\n";
  char line[256];
  std::snprintf(line, sizeof(line), "%-*s %14s %14s %9s\n", static_cast<int>(width), "key", "A", "B", "B/A");
  out += line;
  for (const auto& r : rows) {
    const double q = ratio(r);
    char rq[32] = "-";
    if (!std::isnan(q)) std::snprintf(rq, sizeof(rq), "%.3f", q);
    std::snprintf(line, sizeof(line), "%-*s %14s %14s %9s\n", static_cast<int>(width), r.key.c_str(), cell(r.a).c_str(),
                  cell(r.b).c_str(), rq);
    out += line;
  }
  return out;
}

}  // namespace vegstream::flight
