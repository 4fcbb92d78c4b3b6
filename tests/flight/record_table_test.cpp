// The recorder's data side without a GPU: frames.csv round trip (empty cells stay empty),
// strict CSV reading, percentiles as numpy computes them, the hitch rule, the column layout,
// and compare's B/A ratios.

#include <cmath>

#include <gtest/gtest.h>

#include "flight/compare.h"
#include "flight/record_table.h"
#include "flight/frame_columns.h"
#include "flight/path_sampler.h"
#include "flight/summary.h"

namespace vegstream::flight {
namespace {

TEST(RecorderTable, CsvRoundTripKeepsEmptyCellsEmpty) {
  RecordTable t({{"frame", 0}, {"t_s", 6}, {"cpu_streaming_ms", 4}, {"gpu_frame_ms", 4}});
  auto& r0 = t.addRow();
  r0[0] = 0;
  r0[1] = 0.0;
  r0[3] = 1.25;
  auto& r1 = t.addRow();
  r1[0] = 1;
  r1[1] = 1.0 / 60.0;
  r1[3] = 2.5;
  const std::string csv = t.toCsv();
  EXPECT_EQ(csv, "frame,t_s,cpu_streaming_ms,gpu_frame_ms\n0,0.000000,,1.2500\n1,0.016667,,2.5000\n");
  auto back = RecordTable::parseCsv(csv, "frames.csv");
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back->rowCount(), 2u);
  EXPECT_TRUE(std::isnan(back->at(1, 2)));
  EXPECT_DOUBLE_EQ(back->at(1, 3), 2.5);
  EXPECT_TRUE(back->values(2).empty());
  EXPECT_EQ(back->values(3).size(), 2u);
}

TEST(RecorderTable, StrictReadingNamesLineAndColumn) {
  auto bad = RecordTable::parseCsv("frame,t_s\n0,0\n1,abc\n", "x/frames.csv");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(bad.error().message.find("x/frames.csv:3"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("t_s"), std::string::npos) << bad.error().message;
  auto ragged = RecordTable::parseCsv("frame,t_s\n0\n", "f.csv");
  ASSERT_FALSE(ragged);
  EXPECT_NE(ragged.error().message.find("f.csv:2"), std::string::npos);
  EXPECT_FALSE(RecordTable::parseCsv("", "f.csv"));
}

TEST(RecorderTable, PercentilesInterpolateLikeNumpy) {
  // numpy.percentile([1, 2, 3, 4, 10], q) = 3, 8.8, 9.76, 10 for q = 50, 95, 99, 100.
  const std::vector<double> v = {10, 2, 4, 1, 3};
  EXPECT_DOUBLE_EQ(percentile(v, 50), 3.0);
  EXPECT_NEAR(percentile(v, 95), 8.8, 1e-12);
  EXPECT_NEAR(percentile(v, 99), 9.76, 1e-12);
  EXPECT_DOUBLE_EQ(percentile(v, 100), 10.0);
  EXPECT_TRUE(std::isnan(percentile({}, 50)));
}

TEST(RecorderTable, HitchIsOverTwiceTheRunningMedian) {
  std::vector<double> ms(100, 10.0);
  ms[50] = 20.0;  // exactly 2x: not a hitch
  ms[70] = 20.5;  // over 2x
  ms[90] = 100.0;
  EXPECT_EQ(findHitches(ms), (std::vector<std::size_t>{70, 90}));
  // The median follows the load: after a lasting step to 30 ms, frames at 30 ms are no hitches.
  std::vector<double> step(200, 10.0);
  for (std::size_t i = 100; i < 200; ++i) step[i] = 30.0;
  const auto h = findHitches(step);
  ASSERT_FALSE(h.empty());
  EXPECT_EQ(h.front(), 100u);
  EXPECT_LT(h.back(), 100u + kHitchWindow / 2 + 1);
}

TEST(RecorderTable, FrameCount) {
  EXPECT_EQ(frameCount(30.0, 60.0), 1801u);
  EXPECT_EQ(frameCount(2.0, 15.0), 31u);
  EXPECT_EQ(frameCount(0.1, 15.0), 2u);
}

TEST(RecorderTable, GpuPassColumnNames) {
  EXPECT_EQ(column::gpuPassColumn("sky"), "gpu_sky_ms");
  EXPECT_EQ(column::gpuPassColumn("Terrain pass"), "gpu_terrain_pass_ms");
}

TEST(RecorderTable, CompareRatios) {
  const std::string a =
      R"({"summary_version": 1, "frames": 10, "times_ms": {"gpu_frame_ms": {"p50": 2, "p95": 4, "p99": 5, "max": 6}, "cpu_seeding_ms": null},
                            "hitches": {"count": 0}})";
  const std::string b =
      R"({"summary_version": 1, "frames": 10, "times_ms": {"gpu_frame_ms": {"p50": 3, "p95": 4, "p99": 5, "max": 6}},
                            "hitches": {"count": 2}, "totals": {"wall_s": 1}})";
  auto rows = compareSummaries(a, "a", b, "b");
  ASSERT_TRUE(rows) << rows.error().message;
  const auto find = [&](const std::string& k) {
    for (const auto& r : *rows)
      if (r.key == k) return r;
    ADD_FAILURE() << k;
    return CompareRow{};
  };
  EXPECT_DOUBLE_EQ(ratio(find("frames")), 1.0);
  EXPECT_DOUBLE_EQ(ratio(find("times_ms.gpu_frame_ms.p50")), 1.5);
  EXPECT_TRUE(std::isnan(ratio(find("hitches.count"))));                // A is 0
  EXPECT_TRUE(std::isnan(ratio(find("times_ms.cpu_seeding_ms.p50"))));  // absent
  EXPECT_TRUE(std::isnan(find("totals.wall_s").a));                     // only in B
  const std::string table = formatCompareTable(*rows, "A", "B");
  EXPECT_NE(table.find("1.500"), std::string::npos) << table;
  EXPECT_FALSE(compareSummaries("{}", "a.json", b, "b"));
}

}  // namespace
}  // namespace vegstream::flight
