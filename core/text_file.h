#pragma once
// Reading a whole (small) text file — JSON, CSV — as a value, with the file named in the error.

#include <filesystem>
#include <string>

#include "core/result.h"

namespace vegstream {

// The file's bytes. NotFound: "<file>: <missingHint>" when it cannot be opened; Io when a read
// fails part-way.
Result<std::string> readTextFile(const std::filesystem::path& file, const std::string& missingHint = "no such file");

}  // namespace vegstream
