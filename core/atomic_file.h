#pragma once
// Output that is never half-written: write to a temporary path beside the target, then rename
// into place when complete. If the writer fails or throws, the temporary is removed.

#include <filesystem>
#include <functional>

#include "core/result.h"

namespace vegstream {

// Calls write(tmpPath); on success renames tmpPath → path (atomic on one filesystem).
Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(const std::filesystem::path& tmpPath)>& write);

// Same for a directory: write(tmpDir) fills a fresh temporary directory beside `dir`, which
// then replaces `dir` only if `dir` does not exist or is empty.
Status writeDirectoryAtomically(const std::filesystem::path& dir,
                                const std::function<Status(const std::filesystem::path& tmpDir)>& write);

}  // namespace vegstream
