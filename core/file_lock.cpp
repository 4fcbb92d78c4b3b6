// flock(2)-based exclusive lock file (file_lock.h). The file is unlinked while still locked on
// release; a process that opened it before the unlink sees that its descriptor no longer names
// the path (inode differs or path gone) once it gets the lock, and retries on a fresh file.

#include "core/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/checked_write.h"

namespace vegstream {
namespace fs = std::filesystem;

namespace {
std::string holderPid(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof(buf) - 1, 0);
  std::string pid = n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string("unknown");
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

// Whether `fd` is still the file at `path` (not unlinked or replaced by a releasing holder).
bool sameFile(int fd, const fs::path& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}
}  // namespace

Result<FileLock> FileLock::acquire(const fs::path& lockFile, const std::string& what) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(lockFile.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      return makeError(ErrorKind::Io, "cannot create the lock file '" + lockFile.string() + "': " + ioReason(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string pid = holderPid(fd);
      ::close(fd);
      if (err == EWOULDBLOCK)
        return makeError(ErrorKind::InvalidInput, what + " is in use by another vegstream process (PID " + pid +
                                                      "; lock " + lockFile.string() + ")");
      return makeError(ErrorKind::Io, "cannot lock '" + lockFile.string() + "': " + ioReason(err));
    }
    if (!sameFile(fd, lockFile)) {  // the previous holder removed it between our open and flock
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int err = errno;
      ::unlink(lockFile.c_str());
      ::close(fd);
      return makeError(ErrorKind::Io, "cannot write the lock file '" + lockFile.string() + "': " + ioReason(err));
    }
    return FileLock(lockFile, fd);
  }
  return makeError(ErrorKind::Io, "cannot take the lock file '" + lockFile.string() + "': it keeps being replaced");
}

FileLock::FileLock(FileLock&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) { other.fd_ = -1; }

FileLock::~FileLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still locked: see the comment at the top
  ::close(fd_);
}

}  // namespace vegstream
