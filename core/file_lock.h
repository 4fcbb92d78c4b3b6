#pragma once
// An exclusive lock on a lock file (flock(2)), held while an object lives: a second process
// that asks for the same lock is refused at once instead of writing into the same output.
// The kernel drops the lock when the holder dies (even by SIGKILL), so a killed run never
// blocks the next one. The lock file holds the holder's PID (for the refusal's message) and is
// removed on release; a file left by a killed holder is taken over by the next one.

#include <filesystem>
#include <string>

#include "core/result.h"

namespace vegstream {

class FileLock {
 public:
  // Takes the lock on `lockFile` (created if missing). Refused: InvalidInput
  // "<what> is in use by another vegstream process (PID n; lock <lockFile>)".
  static Result<FileLock> acquire(const std::filesystem::path& lockFile, const std::string& what);
  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&&) = delete;
  FileLock(const FileLock&) = delete;
  ~FileLock();

  const std::filesystem::path& path() const { return path_; }

 private:
  FileLock(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace vegstream
