#pragma once
// Byte-for-byte comparison of two dataset directories' tiles (the files in its layer folders;
// dataset.json and the TileJSONs at the root carry the dataset's name),
// for the tests that say two imports are the same import.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace vegstream::datasets::test {

struct TreeComparison {
  int files = 0;      // files under a (the layer `sub`, or all)
  int different = 0;  // differing in bytes, or missing from b, or only in b
  std::string firstDifference;
};

inline std::string fileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline TreeComparison compareTileTrees(const std::filesystem::path& a, const std::filesystem::path& b,
                                       const std::string& sub = "") {
  namespace fs = std::filesystem;
  TreeComparison c;
  const auto note = [&](const std::string& what) {
    ++c.different;
    if (c.firstDifference.empty()) c.firstDifference = what;
  };
  if (!fs::is_directory(a / sub) || !fs::is_directory(b / sub)) {
    note("no directory " + (a / sub).string() + " or " + (b / sub).string());
    return c;
  }
  for (const auto& e : fs::recursive_directory_iterator(a / sub)) {
    if (!e.is_regular_file() || e.path().parent_path() == a) continue;
    ++c.files;
    const fs::path rel = fs::relative(e.path(), a);
    if (!fs::exists(b / rel))
      note(rel.string() + " missing from " + b.string());
    else if (fileBytes(e.path()) != fileBytes(b / rel))
      note(rel.string() + " differs");
  }
  for (const auto& e : fs::recursive_directory_iterator(b / sub)) {
    if (!e.is_regular_file() || e.path().parent_path() == b) continue;
    if (!fs::exists(a / fs::relative(e.path(), b))) note(fs::relative(e.path(), b).string() + " only in " + b.string());
  }
  return c;
}

}  // namespace vegstream::datasets::test
