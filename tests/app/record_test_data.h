#pragma once
// Shared inputs of the recording tests: a small generated dataset (4 km, 46.55 N 7.95 E) made
// once per build for all test processes (cachedFixture), and a 2-second path over its
// middle written into the test's own directory.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

// `name` in the running test's own directory.
inline std::filesystem::path recordTmp(const std::string& name) { return testOutputDir() / name; }

// The same, removed (for an --out that must not exist).
inline std::filesystem::path freshRecordDir(const std::string& name) {
  const auto dir = recordTmp(name);
  std::filesystem::remove_all(dir);
  return dir;
}

// The generated dataset; a test that cannot have it fails (the path returned then does not exist).
inline std::filesystem::path recordDataset() {
  const auto dir = cachedFixture("record-dataset-4km", vegstreamKey(), [](const std::filesystem::path& out) -> Status {
    const auto r = runVegstream("generate --out '" + out.string() + "' --lat 46.55 --lon 7.95 --size-km 4 --seed 1");
    if (r.exitCode != 0) return makeError(ErrorKind::Internal, "vegstream generate: " + r.err);
    return {};
  });
  if (!dir.ok()) {
    ADD_FAILURE() << dir.error().message;
    return "/nonexistent/record-dataset";
  }
  return *dir;
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
