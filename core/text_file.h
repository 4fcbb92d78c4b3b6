#pragma once
// Reading a whole (small) text file — JSON, CSV — as a value, with the file named in the error.
// Goes through the checked opener (regular_file.h): only a regular file, at most the ceiling.

#include <filesystem>
#include <string>

#include "core/regular_file.h"
#include "core/result.h"

namespace vegstream {

// The file's bytes. NotFound: "<file>: <missingHint>" when it does not exist; InvalidInput when
// it is no regular file or is larger than the ceiling; Io when a read fails part-way.
Result<std::string> readTextFile(const std::filesystem::path& file, const std::string& missingHint = "no such file",
                                 const FileCeiling& ceiling = kJsonFileCeiling);

}  // namespace vegstream
