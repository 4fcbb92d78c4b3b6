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

// Runs write(tmp); on failure or exception removes tmp; on success renames tmp → target
// (replacing an empty directory, the only kind of existing target the callers allow).
Status writeThenRename(const fs::path& tmp, const fs::path& target,
                       const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
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
  if (fs::is_directory(target, ec) && fs::is_directory(tmp, ec)) fs::remove(target, ec);
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string reason = ec.message();
    fs::remove_all(tmp, ec);
    return makeError(ErrorKind::Io, "cannot move " + tmp.string() + " to " + target.string() + ": " + reason);
  }
  return {};
}

Status createDirectories(const fs::path& dir) {
  std::error_code ec;
  if (!dir.empty()) fs::create_directories(dir, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create directory " + dir.string() + ": " + ec.message());
  return {};
}
}  // namespace

Status writeFileAtomically(const fs::path& path, const std::function<Status(const fs::path&)>& write) {
  if (Status s = createDirectories(path.parent_path()); !s) return s;
  return writeThenRename(temporaryBeside(path), path, write);
}

Status writeDirectoryAtomically(const fs::path& dir, const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
    return makeError(ErrorKind::InvalidInput,
                     dir.string() + " already exists and is not empty; choose another output directory");
  if (Status s = createDirectories(dir.parent_path().empty() ? fs::path(".") : dir.parent_path()); !s) return s;
  const fs::path tmp = temporaryBeside(dir);
  if (Status s = createDirectories(tmp); !s) return s;
  return writeThenRename(tmp, dir, write);
}

}  // namespace vegstream
