// Checked writes and fsync (checked_write.h): POSIX calls, so that every error has an errno.

#include "core/checked_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vegstream {
namespace fs = std::filesystem;

namespace {
// Closes the descriptor; a close error (NFS reports failed writes here) is returned as errno.
int closeChecked(int fd) { return ::close(fd) == 0 ? 0 : errno; }
}  // namespace

std::string ioReason(int err) {
  switch (err) {
    case ENOSPC: return "disk full";
    case EDQUOT: return "disk quota exceeded";
    case EFBIG: return "file too large (" + std::string(std::strerror(err)) + ")";
    default: return std::strerror(err);
  }
}

Error writeError(const fs::path& file, int err) {
  return makeError(ErrorKind::Io, "cannot write '" + file.string() + "': " + ioReason(err));
}

namespace {
// Closes fd after a failed call whose errno is err (a close error then adds nothing), and
// returns err's error.
Error closeAfterError(int fd, int err, const fs::path& nameForErrors) {
  ::close(fd);
  return writeError(nameForErrors, err);
}

// Closes fd after its sync: syncErr is the sync's errno (0: it succeeded). The sync's error is
// returned first, else the close's; fd is closed either way.
Status closeAfterSync(int fd, int syncErr, const fs::path& nameForErrors) {
  if (syncErr != 0) return closeAfterError(fd, syncErr, nameForErrors);
  if (const int err = closeChecked(fd); err != 0) return writeError(nameForErrors, err);
  return {};
}
}  // namespace

Status writeAllBytes(const fs::path& file, std::span<const uint8_t> bytes, const fs::path& nameForErrors) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return writeError(nameForErrors, errno);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return closeAfterError(fd, n < 0 ? errno : EIO, nameForErrors);
    done += static_cast<size_t>(n);
  }
  return closeAfterSync(fd, ::fsync(fd) != 0 ? errno : 0, nameForErrors);
}

Status writeAllText(const fs::path& file, std::string_view text, const fs::path& nameForErrors) {
  return writeAllBytes(file, {reinterpret_cast<const uint8_t*>(text.data()), text.size()}, nameForErrors);
}

Status syncPath(const fs::path& path, const fs::path& nameForErrors) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return writeError(nameForErrors, errno);
  // EINVAL: a file system without fsync for this kind of file.
  return closeAfterSync(fd, ::fsync(fd) != 0 && errno != EINVAL ? errno : 0, nameForErrors);
}

Status syncDirectoryTree(const fs::path& dir, const fs::path& nameForErrors) {
  // One syncfs(2) of the file system holding `dir` flushes every file and directory under it,
  // far cheaper than an fsync per tile of a dataset.
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return writeError(nameForErrors, errno);
  return closeAfterSync(fd, ::syncfs(fd) != 0 ? errno : 0, nameForErrors);
}

}  // namespace vegstream
