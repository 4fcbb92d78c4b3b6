#pragma once
// Shared inputs of the recording tests: a small generated dataset (4 km, 46.55 N 7.95 E) and a
// 2-second path over its middle, made once per build tree and reused (every writer is atomic,
// so an existing dataset.json means a complete dataset).

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_command.h"

namespace vegstream::testing {

// Shared by the tests of one build: the directories carry the executable's time stamp, so a
// rebuilt vegstream never meets recordings or datasets an older one made.
inline std::filesystem::path recordTmp(const std::string& name) {
  std::error_code ec;
  const auto stamp = std::filesystem::last_write_time(VEGSTREAM_EXE, ec).time_since_epoch().count();
  const auto dir = std::filesystem::path(VEGSTREAM_TEST_TMP) / ("b" + std::to_string(stamp));
  std::filesystem::create_directories(dir, ec);
  return dir / name;
}

inline std::filesystem::path freshRecordDir(const std::string& name) {
  const auto dir = recordTmp(name);
  std::filesystem::remove_all(dir);
  return dir;
}

// The generated dataset (made on first use).
inline std::filesystem::path recordDataset() {
  const auto dir = recordTmp("record_dataset");
  if (!std::filesystem::exists(dir / "dataset.json")) {
    const auto r = runVegstream("generate --out '" + dir.string() + "' --lat 46.55 --lon 7.95 --size-km 4 --seed 1");
    // A parallel test may have made it first.
    EXPECT_TRUE(r.exitCode == 0 || std::filesystem::exists(dir / "dataset.json")) << r.err;
  }
  return dir;
}

// A 2 s flight path over the dataset's middle, 300 m above the terrain.
inline std::filesystem::path recordPath() {
  const auto file = recordTmp("record_path_2s.json");
  std::ofstream(file) << R"({"name": "test-2s", "keyframes": [
  {"t": 0, "lat": 46.545, "lon": 7.945, "alt_m": 300, "heading": 30, "pitch": -20},
  {"t": 2, "lat": 46.555, "lon": 7.955, "alt_m": 150, "heading": 60, "pitch": -10}]})";
  return file;
}

// `vegstream record` of recordPath over recordDataset at 160x90, MSAA 1, 15 fps (31 frames).
inline CommandResult recordSmall(const std::filesystem::path& out, const std::string& extra = "") {
  return runVegstream("record '" + recordDataset().string() + "' --path '" + recordPath().string() + "' --out '" +
                      out.string() + "' --size 160x90 --msaa 1 --fps 15 " + extra);
}

}  // namespace vegstream::testing
