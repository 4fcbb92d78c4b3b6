#include "core/atomic_file.h"

#include <atomic>
#include <string>
#include <system_error>
#include <unistd.h>

namespace vegstream {
namespace fs = std::filesystem;

namespace {
// A name beside `target` that no other writer in this or another process picks.
fs::path temporaryBeside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  fs::path name = target.filename();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return target.parent_path() / name;
}
}  // namespace

Status writeFileAtomically(const fs::path& path, const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path(), ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create directory " + path.parent_path().string() + ": " + ec.message());
  const fs::path tmp = temporaryBeside(path);
  Status status;
  try {
    status = write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  if (!status) {
    fs::remove(tmp, ec);
    return status;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return makeError(ErrorKind::Io, "cannot move " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
  return {};
}

Status writeDirectoryAtomically(const fs::path& dir, const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
    return makeError(ErrorKind::InvalidInput, dir.string() + " already exists and is not empty; choose another output directory");
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  fs::create_directories(parent, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create directory " + parent.string() + ": " + ec.message());
  const fs::path tmp = temporaryBeside(dir);
  fs::create_directories(tmp, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create directory " + tmp.string() + ": " + ec.message());
  Status status;
  try {
    status = write(tmp);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  if (!status) {
    fs::remove_all(tmp, ec);
    return status;
  }
  if (fs::exists(dir, ec)) fs::remove(dir, ec);  // the empty directory it replaces
  fs::rename(tmp, dir, ec);
  if (ec) {
    fs::remove_all(tmp, ec);
    return makeError(ErrorKind::Io, "cannot move " + tmp.string() + " to " + dir.string() + ": " + ec.message());
  }
  return {};
}

}  // namespace vegstream
