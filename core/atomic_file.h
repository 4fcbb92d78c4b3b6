#pragma once
// Output that is never half-written: write to a temporary path beside the target
// ("NAME.tmp-PID-N"), check every write, fsync it, rename it over the target, fsync the
// directory. If the writer fails or throws, the temporary is removed and the old target stays
// exactly as it was; the error is one line naming the target and the OS's reason (checked_write.h).
// Temporaries that a killed process left beside the target (its PID no longer runs) are removed
// by the next write of the same target.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>

#include "core/result.h"

namespace vegstream {

// Calls write(tmpPath); on success fsyncs tmpPath and renames it → path (atomic on one file
// system), then fsyncs path's directory. `write` must report its own failures; it should write
// through writeAllBytes (checked_write.h) or check its stream's state after close.
Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(const std::filesystem::path& tmpPath)>& write);

// The common cases: the whole content already in memory.
Status writeBytesAtomically(const std::filesystem::path& path, std::span<const uint8_t> bytes);
Status writeTextAtomically(const std::filesystem::path& path, std::string_view text);

// Two or more files that belong together (a still and its sidecar): each is staged (written,
// checked and fsynced under its temporary name) before any is renamed, so a failure while
// writing leaves every old file as it was. A staged file that is not committed is removed.
class StagedFile {
 public:
  static Result<StagedFile> stage(const std::filesystem::path& path, std::span<const uint8_t> bytes);
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  ~StagedFile();
  // Renames the temporary over the target and fsyncs the directory.
  Status commit();

 private:
  StagedFile(std::filesystem::path path, std::filesystem::path tmp) : path_(std::move(path)), tmp_(std::move(tmp)) {}
  std::filesystem::path path_, tmp_;
};

// Same for a directory: write(tmpDir) fills a fresh temporary directory beside `dir`, which is
// fsynced (every entry) and then replaces `dir` only if `dir` does not exist or is empty.
Status writeDirectoryAtomically(const std::filesystem::path& dir,
                                const std::function<Status(const std::filesystem::path& tmpDir)>& write);

// Removes "NAME.tmp-PID-N" entries beside `target` whose PID is not a running process (and is
// not this one). Returns how many were removed. Called by the two functions above.
size_t removeStaleTemporaries(const std::filesystem::path& target);

// Whether `name` is a temporary of core/atomic_file ("….tmp-PID-N"), and its PID if so.
bool parseTemporaryName(std::string_view name, long* pid);

}  // namespace vegstream
