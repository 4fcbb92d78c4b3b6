// The sun in the frames (issue 39) through the real executable on lavapipe, over the small
// generated dataset of the recording tests: recording.json's date-time and sun, frames.csv's sun
// columns following the flight clock, where the date-time comes from (--datetime over the path's
// "datetime" over the imagery's over the default), a path's or a dataset's bad date-time named
// with its place, and a still's sidecar F.json.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "geo/datetime.h"
#include "geo/solar_position.h"
#include "tests/app/record_test_data.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

std::int64_t msOf(const std::string& iso) {
  const auto t = geo::parseIsoDateTime(iso);
  EXPECT_TRUE(t.ok()) << iso;
  return t.ok() ? t->unixMs : 0;
}

// A 2 s path over the dataset's middle with `datetimeLine` (e.g. "\"datetime\": \"…\",") on line 2.
fs::path pathWith(const std::string& name, const std::string& datetimeLine) {
  const fs::path file = recordTmp(name);
  std::ofstream(file) << "{\"name\": \"sun-2s\",\n  " << datetimeLine << R"(
  "keyframes": [
  {"t": 0, "lat": 46.545, "lon": 7.945, "alt_m": 300, "heading": 30, "pitch": -20},
  {"t": 2, "lat": 46.555, "lon": 7.955, "alt_m": 150, "heading": 60, "pitch": -10}]})";
  return file;
}

// `record` at 2 fps (5 frames), 160x90, no plots.
CommandResult recordQuick(const fs::path& dataset, const fs::path& path, const fs::path& out,
                          const std::string& extra = "") {
  return runVegstream("record '" + dataset.string() + "' --path '" + path.string() + "' --out '" + out.string() +
                      "' --size 160x90 --msaa 1 --fps 2 --no-plots " + extra);
}

json readJson(const fs::path& file) {
  std::ifstream f(file);
  return json::parse(f, nullptr, false);
}

// The CSV's rows as cells, with the header.
std::vector<std::vector<std::string>> readRows(const fs::path& file) {
  std::ifstream f(file);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(f, line);) {
    rows.emplace_back();
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) rows.back().push_back(cell);
  }
  return rows;
}

std::size_t columnOf(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << name;
  return static_cast<std::size_t>(it - header.begin());
}

TEST(SunFrames, TheRecordingFollowsTheDatetimeAndTheFlightClock) {
  const fs::path out = freshRecordDir("sun_record");
  const auto r = recordSmall(out, "--no-plots --frames-every 15 --datetime 2015-08-18T17:58:00Z");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json rec = readJson(out / "recording.json");
  EXPECT_EQ(rec["datetime"], "2015-08-18T17:58:00Z");
  EXPECT_EQ(rec["datetime_source"], "option");
  EXPECT_TRUE(rec["exposure_ev"].is_null());
  const double lat = rec["sun"]["lat"], lon = rec["sun"]["lon"];
  EXPECT_NEAR(lat, 46.55, 0.05) << "the dataset's centre";
  EXPECT_NEAR(lon, 7.95, 0.05);
  const std::int64_t t0 = msOf("2015-08-18T17:58:00Z");
  const geo::SolarPosition start = geo::solarPosition(t0, lat, lon);
  EXPECT_DOUBLE_EQ(rec["sun"]["azimuth_deg"].get<double>(), start.azimuthDeg);
  EXPECT_DOUBLE_EQ(rec["sun"]["elevation_deg"].get<double>(), start.elevationDeg);

  const auto rows = readRows(out / "frames.csv");
  ASSERT_EQ(rows.size(), 32u) << "header + 31 frames";
  const std::size_t tc = columnOf(rows[0], "t_s"), az = columnOf(rows[0], "sun_azimuth_deg"),
                    el = columnOf(rows[0], "sun_elevation_deg");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double t = std::stod(rows[i].at(tc));
    const geo::SolarPosition sun = geo::solarPosition(t0 + std::llround(t * 1000.0), lat, lon);
    EXPECT_NEAR(std::stod(rows[i].at(az)), sun.azimuthDeg, 6e-5) << "frame " << i - 1;
    EXPECT_NEAR(std::stod(rows[i].at(el)), sun.elevationDeg, 6e-5) << "frame " << i - 1;
  }
  // 19:58 in the Alps in August: the evening sun sinks and moves north-west over the 2 s.
  EXPECT_LT(std::stod(rows.back().at(el)), std::stod(rows[1].at(el)));
  EXPECT_GT(std::stod(rows.back().at(az)), std::stod(rows[1].at(az)));
  EXPECT_GT(start.azimuthDeg, 270.0);
  EXPECT_LT(start.elevationDeg, 15.0);

  // The saved frame 15 (t = 1 s) has its sidecar: the same sun as its row, one second on.
  const json side = readJson(out / "frames" / "frame_00015.json");
  ASSERT_FALSE(side.is_discarded());
  EXPECT_EQ(side["datetime"], "2015-08-18T17:58:01Z");
  EXPECT_NEAR(side["sun"]["azimuth_deg"].get<double>(), std::stod(rows[16].at(az)), 6e-5);
  EXPECT_NEAR(side["sun"]["elevation_deg"].get<double>(), std::stod(rows[16].at(el)), 6e-5);
  EXPECT_NEAR(side["pose"]["lat"].get<double>(), std::stod(rows[16].at(columnOf(rows[0], "lat"))), 1e-8);
  EXPECT_EQ(side["size"], json({{"width", 160}, {"height", 90}}));
  EXPECT_GT(side["counts"]["terrain_triangles"].get<double>(), 0.0);
}

TEST(SunFrames, ThePathsDatetimeIsUsedAndTheCommandLineWins) {
  const fs::path path = pathWith("sun_path.json", R"("datetime": "2026-06-21T06:45:00-06:00",)");
  const fs::path a = freshRecordDir("sun_path_a"), b = freshRecordDir("sun_path_b");
  const auto ra = recordQuick(recordDataset(), path, a);
  ASSERT_EQ(ra.exitCode, 0) << ra.err;
  EXPECT_EQ(readJson(a / "recording.json")["datetime"], "2026-06-21T06:45:00-06:00");
  EXPECT_EQ(readJson(a / "recording.json")["datetime_source"], "option");
  const auto rb = recordQuick(recordDataset(), path, b, "--datetime 2015-08-18T17:58:00.250Z --exposure 3.5");
  ASSERT_EQ(rb.exitCode, 0) << rb.err;
  const json rec = readJson(b / "recording.json");
  EXPECT_EQ(rec["datetime"], "2015-08-18T17:58:00.250Z");
  EXPECT_EQ(rec["exposure_ev"], 3.5);
}

TEST(SunFrames, APathsBadDatetimeIsNamedWithItsLineAndColumn) {
  const fs::path path = pathWith("sun_bad_path.json", R"("datetime": "2026-13-01T00:00:00Z",)");
  const fs::path out = freshRecordDir("sun_bad_path_out");
  const auto r = recordQuick(recordDataset(), path, out);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(path.string() + ":2:15: datetime: \"2026-13-01T00:00:00Z\": month 13 does not exist"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// A copy of the generated dataset whose dataset.json says when its imagery was taken.
fs::path datasetWithImageryDatetime(const std::string& name, const std::string& datetime) {
  const fs::path dir = recordTmp(name);
  fs::remove_all(dir);
  fs::copy(recordDataset(), dir, fs::copy_options::recursive);
  json meta = readJson(dir / "dataset.json");
  meta["imagery"]["datetime"] = datetime;
  std::ofstream(dir / "dataset.json") << meta.dump(2);
  return dir;
}

TEST(SunFrames, WithoutADatetimeTheImageryTimeElseTheDefaultSun) {
  const fs::path path = pathWith("sun_plain.json", "");
  const fs::path plain = freshRecordDir("sun_default"), dated = freshRecordDir("sun_dataset");
  const auto r = recordQuick(recordDataset(), path, plain);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json rec = readJson(plain / "recording.json");
  EXPECT_EQ(rec["datetime_source"], "default");
  EXPECT_EQ(rec["datetime"], "2024-06-21T10:00:00+00:32") << "10:00 local mean solar time at 7.95° E";
  EXPECT_GT(rec["sun"]["elevation_deg"].get<double>(), 45.0) << "a mid-morning summer sun";

  const fs::path dataset = datasetWithImageryDatetime("sun_dataset_copy", "2015-08-18T10:30:00+02:00");
  const auto rd = recordQuick(dataset, path, dated);
  ASSERT_EQ(rd.exitCode, 0) << rd.err;
  EXPECT_EQ(readJson(dated / "recording.json")["datetime_source"], "dataset");
  EXPECT_EQ(readJson(dated / "recording.json")["datetime"], "2015-08-18T10:30:00+02:00");
}

TEST(SunFrames, ADatasetsBadImageryDatetimeNamesTheFileAndField) {
  const fs::path dataset = datasetWithImageryDatetime("sun_bad_dataset", "2015-08-18");
  const fs::path out = freshRecordDir("sun_bad_dataset_out");
  const auto r = recordQuick(dataset, pathWith("sun_plain2.json", ""), out);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find((dataset / "dataset.json").string() + "': field 'imagery.datetime' \"2015-08-18\": no time"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(SunFrames, ASnapshotsSidecarHoldsThePoseTheSunTheExposureAndTheCounts) {
  const fs::path dir = testOutputDir(), png = dir / "still.png";
  const auto r = runVegstream("snapshot '" + recordDataset().string() +
                              "' --lat 46.552 --lon 7.951 --alt 300 --heading 30 --pitch -30 --size 160x90 --msaa 1 "
                              "--validate --datetime 2026-06-21T06:45:00-06:00 --exposure 2 --out '" +
                              png.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"still.json", "still.png"})) << "the still, its sidecar, nothing else";

  const json s = readJson(dir / "still.json");
  ASSERT_FALSE(s.is_discarded());
  EXPECT_DOUBLE_EQ(s["pose"]["lat"].get<double>(), 46.552);
  EXPECT_DOUBLE_EQ(s["pose"]["lon"].get<double>(), 7.951);
  EXPECT_NEAR(s["pose"]["alt_m_above_ground"].get<double>(), 300.0, 1e-6);
  EXPECT_GT(s["pose"]["alt_m_msl"].get<double>(), 300.0);
  EXPECT_DOUBLE_EQ(s["pose"]["heading_deg"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(s["pose"]["pitch_deg"].get<double>(), -30.0);
  EXPECT_GT(s["vertical_fov_deg"].get<double>(), 10.0);
  EXPECT_LT(s["vertical_fov_deg"].get<double>(), 120.0);
  EXPECT_EQ(s["datetime"], "2026-06-21T06:45:00-06:00");
  const geo::SolarPosition sun =
      geo::solarPosition(msOf("2026-06-21T06:45:00-06:00"), s["sun"]["lat"].get<double>(), s["sun"]["lon"].get<double>());
  EXPECT_DOUBLE_EQ(s["sun"]["azimuth_deg"].get<double>(), sun.azimuthDeg);
  EXPECT_DOUBLE_EQ(s["sun"]["elevation_deg"].get<double>(), sun.elevationDeg);
  EXPECT_NEAR(s["sun"]["lat"].get<double>(), 46.55, 0.05);
  // 12:45 UTC in the Alps on the solstice: early afternoon, high in the south-south-west.
  EXPECT_GT(sun.azimuthDeg, 180.0);
  EXPECT_LT(sun.azimuthDeg, 240.0);
  EXPECT_GT(sun.elevationDeg, 55.0);
  EXPECT_TRUE(s["exposure_ev"].is_number());
  EXPECT_EQ(s["exposure_mode"], "fixed");
  EXPECT_EQ(s["size"], json({{"width", 160}, {"height", 90}}));
  EXPECT_GT(s["counts"]["terrain_triangles"].get<double>(), 0.0);
  EXPECT_TRUE(s["counts"].contains("seed_triangles"));
  EXPECT_TRUE(s["counts"].contains("plants"));
  EXPECT_TRUE(s["counts"].contains("trees"));
}

}  // namespace
}  // namespace vegstream::testing
