// Write-to-temporary, check, fsync, rename (atomic_file.h).

#include "core/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include "core/checked_write.h"

namespace vegstream {
namespace fs = std::filesystem;

namespace {
constexpr std::string_view kMarker = ".tmp-";

// A name beside `target` that no other writer in this or another process picks.
fs::path temporaryBeside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  fs::path name = target.filename();
  name += std::string(kMarker) + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return target.parent_path() / name;
}

fs::path directoryOf(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

bool processRuns(long pid) { return pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH; }

// Runs write(tmp) and makes tmp durable; on failure or exception removes tmp; on success
// renames tmp → target (replacing an empty directory, the only kind of existing directory
// target the callers allow) and fsyncs the target's directory.
Status writeThenRename(const fs::path& tmp, const fs::path& target, bool isDirectory,
                       const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  Status status;
  try {
    status = write(tmp);
    if (status) status = isDirectory ? syncDirectoryTree(tmp, target) : syncPath(tmp, target);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  if (!status) {
    fs::remove_all(tmp, ec);
    return status;
  }
  if (isDirectory && fs::is_directory(target, ec)) fs::remove(target, ec);
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string reason = ec.message();
    fs::remove_all(tmp, ec);
    return makeError(ErrorKind::Io, "cannot move " + tmp.string() + " to " + target.string() + ": " + reason);
  }
  return syncPath(directoryOf(target), target);
}

Status createDirectories(const fs::path& dir) {
  std::error_code ec;
  if (!dir.empty()) fs::create_directories(dir, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create directory " + dir.string() + ": " + ec.message());
  return {};
}
}  // namespace

bool parseTemporaryName(std::string_view name, long* pid) {
  const size_t at = name.rfind(kMarker);
  if (at == std::string_view::npos || at == 0) return false;
  const std::string_view rest = name.substr(at + kMarker.size());
  const size_t dash = rest.find('-');
  if (dash == std::string_view::npos || dash == 0 || dash + 1 == rest.size()) return false;
  long p = 0;
  unsigned long n = 0;
  const auto a = std::from_chars(rest.data(), rest.data() + dash, p);
  const auto b = std::from_chars(rest.data() + dash + 1, rest.data() + rest.size(), n);
  // After N: nothing, or the extension a writer needed (".gpkg") and what SQLite adds ("-wal").
  const bool endsWell = b.ptr == rest.data() + rest.size() || *b.ptr == '.';
  if (a.ec != std::errc() || a.ptr != rest.data() + dash || b.ec != std::errc() || !endsWell || p <= 0) return false;
  if (pid) *pid = p;
  return true;
}

size_t removeStaleTemporaries(const fs::path& target) {
  const std::string prefix = target.filename().string() + std::string(kMarker);
  std::error_code ec;
  std::vector<fs::path> stale;
  for (auto it = fs::directory_iterator(directoryOf(target), ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    long pid = 0;
    if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() && name.find(kMarker, prefix.size()) == std::string::npos &&
        parseTemporaryName(name, &pid) && !processRuns(pid))
      stale.push_back(it->path());
  }
  for (const fs::path& p : stale) fs::remove_all(p, ec);
  return stale.size();
}

Status writeFileAtomically(const fs::path& path, const std::function<Status(const fs::path&)>& write) {
  if (Status s = createDirectories(path.parent_path()); !s) return s;
  removeStaleTemporaries(path);
  return writeThenRename(temporaryBeside(path), path, false, write);
}

Status writeBytesAtomically(const fs::path& path, std::span<const uint8_t> bytes) {
  return writeFileAtomically(path, [&](const fs::path& tmp) { return writeAllBytes(tmp, bytes, path); });
}

Status writeTextAtomically(const fs::path& path, std::string_view text) {
  return writeFileAtomically(path, [&](const fs::path& tmp) { return writeAllText(tmp, text, path); });
}

Result<StagedFile> StagedFile::stage(const fs::path& path, std::span<const uint8_t> bytes) {
  if (Status s = createDirectories(path.parent_path()); !s) return s.error();
  removeStaleTemporaries(path);
  const fs::path tmp = temporaryBeside(path);
  if (Status s = writeAllBytes(tmp, bytes, path); !s) {
    std::error_code ec;
    fs::remove(tmp, ec);
    return s.error();
  }
  return StagedFile(path, tmp);
}

StagedFile::StagedFile(StagedFile&& other) noexcept : path_(std::move(other.path_)), tmp_(std::move(other.tmp_)) {
  other.tmp_.clear();
}

StagedFile::~StagedFile() {
  std::error_code ec;
  if (!tmp_.empty()) fs::remove(tmp_, ec);
}

Status StagedFile::commit() {
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot move " + tmp_.string() + " to " + path_.string() + ": " + ec.message());
  tmp_.clear();
  return syncPath(directoryOf(path_), path_);
}

Status writeDirectoryAtomically(const fs::path& given, const std::function<Status(const fs::path&)>& write) {
  const fs::path dir = given.filename().empty() && given.has_parent_path() ? given.parent_path() : given;  // "out/"
  std::error_code ec;
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
    return makeError(ErrorKind::InvalidInput,
                     dir.string() + " already exists and is not empty; choose another output directory");
  if (Status s = createDirectories(directoryOf(dir)); !s) return s;
  removeStaleTemporaries(dir);
  const fs::path tmp = temporaryBeside(dir);
  if (Status s = createDirectories(tmp); !s) return s;
  return writeThenRename(tmp, dir, true, write);
}

}  // namespace vegstream
