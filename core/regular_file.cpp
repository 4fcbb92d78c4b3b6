// The checked opener (regular_file.h): open(O_RDONLY | O_NONBLOCK), fstat on the descriptor,
// the ceiling against st_size, then reads that stop at the ceiling even when the file grows.

#include "core/regular_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/printable.h"

namespace vegstream {
namespace {

// Closes the descriptor on every way out.
struct Fd {
  int fd = -1;
  Fd() = default;
  Fd(Fd&& o) noexcept : fd(std::exchange(o.fd, -1)) {}
  Fd& operator=(Fd&&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

struct Opened {
  Fd fd;
  uint64_t size = 0;
};

Error fileError(ErrorKind kind, const std::filesystem::path& file, const std::string& problem) {
  return makeError(kind, printablePath(file) + ": " + problem);
}

const char* notRegularWhat(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory, not a file";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

std::string sizeText(uint64_t bytes) {
  if (bytes >= 10 * kMiB) return std::to_string(bytes / kMiB) + " MiB";
  return std::to_string(bytes) + " bytes";
}

Error tooLarge(const std::filesystem::path& file, uint64_t size, const FileCeiling& ceiling) {
  return fileError(ErrorKind::InvalidInput, file,
                   "has " + sizeText(size) + "; " + ceiling.what + " is at most " + sizeText(ceiling.maxBytes));
}

// Reads until end of file, refusing to go past the ceiling (a file that grows while read).
Status readAll(int fd, const std::filesystem::path& file, const FileCeiling& ceiling, uint64_t sizeHint,
               std::vector<uint8_t>& out) {
  out.resize(static_cast<size_t>(sizeHint) + 1);  // one more: end of file is seen without a regrow
  size_t got = 0;
  for (;;) {
    if (got == out.size()) {
      if (got > ceiling.maxBytes) return tooLarge(file, got, ceiling);
      out.resize(std::min<uint64_t>(got * 2 + 4096, ceiling.maxBytes + 1));
    }
    const ssize_t n = ::read(fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fileError(ErrorKind::Io, file, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;
    got += static_cast<size_t>(n);
  }
  if (got > ceiling.maxBytes) return tooLarge(file, got, ceiling);
  out.resize(got);
  return {};
}

// open(O_NONBLOCK) and fstat on the same descriptor: a regular file, or one line saying what
// the path is instead. Blocking reads from here on (a regular file never blocks).
Result<Opened> openRegular(const std::filesystem::path& file, const std::string& missingHint) {
  Opened o;
  do {
    o.fd.fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  } while (o.fd.fd < 0 && errno == EINTR);
  if (o.fd.fd < 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) return fileError(ErrorKind::NotFound, file, missingHint);
    if (err == EACCES || err == EPERM) return fileError(ErrorKind::InvalidInput, file, "permission denied");
    if (err == ELOOP) return fileError(ErrorKind::InvalidInput, file, "too many levels of symbolic links");
    if (err == ENXIO) return fileError(ErrorKind::InvalidInput, file, notRegularWhat(S_IFSOCK));
    return fileError(ErrorKind::InvalidInput, file, std::string("cannot open: ") + std::strerror(err));
  }
  struct stat st {};
  if (::fstat(o.fd.fd, &st) != 0)
    return fileError(ErrorKind::Io, file, std::string("cannot stat: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return fileError(ErrorKind::InvalidInput, file, notRegularWhat(st.st_mode));
  o.size = static_cast<uint64_t>(st.st_size);
  const int flags = ::fcntl(o.fd.fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(o.fd.fd, F_SETFL, flags & ~O_NONBLOCK);
  return o;
}

}  // namespace

Result<std::vector<uint8_t>> readRegularFileBytes(const std::filesystem::path& file, const FileCeiling& ceiling,
                                                  const std::string& missingHint) {
  auto opened = openRegular(file, missingHint);
  if (!opened) return opened.error();
  if (opened->size > ceiling.maxBytes) return tooLarge(file, opened->size, ceiling);
  std::vector<uint8_t> bytes;
  Status s = readAll(opened->fd.fd, file, ceiling, opened->size, bytes);
  if (!s) return s.error();
  return bytes;
}

Result<std::string> readRegularFileHead(const std::filesystem::path& file, size_t maxBytes,
                                        const std::string& missingHint) {
  auto opened = openRegular(file, missingHint);
  if (!opened) return opened.error();
  std::string head(maxBytes, '\0');
  size_t got = 0;
  while (got < maxBytes) {
    const ssize_t n = ::read(opened->fd.fd, head.data() + got, maxBytes - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fileError(ErrorKind::Io, file, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;
    got += static_cast<size_t>(n);
  }
  head.resize(got);
  return head;
}

Result<std::string> readRegularFile(const std::filesystem::path& file, const FileCeiling& ceiling,
                                    const std::string& missingHint) {
  auto bytes = readRegularFileBytes(file, ceiling, missingHint);
  if (!bytes) return bytes.error();
  return std::string(bytes->begin(), bytes->end());
}

}  // namespace vegstream
