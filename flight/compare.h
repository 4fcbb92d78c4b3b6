#pragma once
// `vegstream compare A B`: the figures of two recordings' summary.json side by side with the
// ratio B/A, as a text table (the overlay plot is report.h's makeComparePlot).

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::flight {

struct CompareRow {
  std::string key;  // summary.json path, e.g. "times_ms.gpu_frame_ms.p95"
  double a = 0.0;   // NaN: absent or null in that summary
  double b = 0.0;
};

// The comparable numbers of two summary.json texts: frames, flight time, p50/p95/p99/max of
// every time column, hitch count, peak memory, resident bytes, totals, mean counts, recorder
// overhead. Keys of either side appear (A's order first).
Result<std::vector<CompareRow>> compareSummaries(const std::string& summaryA, const std::string& sourceA,
                                                 const std::string& summaryB, const std::string& sourceB);

// Reads DIR_A/summary.json and DIR_B/summary.json (NotFound / InvalidInput naming the file).
Result<std::vector<CompareRow>> compareRecordings(const std::filesystem::path& dirA, const std::filesystem::path& dirB);

// B/A; NaN when either is missing or A is 0 (the table prints "-").
double ratio(const CompareRow& row);

// The table: a header naming A and B, then "key  A  B  B/A" per row.
std::string formatCompareTable(const std::vector<CompareRow>& rows, const std::string& nameA, const std::string& nameB);

}  // namespace vegstream::flight
