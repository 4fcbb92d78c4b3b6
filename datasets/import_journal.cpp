// The partial directory and journal of an import (import_journal.h).

#include "datasets/import_journal.h"

#include <unistd.h>

#include <cinttypes>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "core/regular_file.h"
#include "core/checked_write.h"
#include "core/file_lock.h"
#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

uint64_t key(const geo::TileId& id) {
  return (static_cast<uint64_t>(id.z) << 58) | (static_cast<uint64_t>(id.x) << 29) | static_cast<uint64_t>(id.y);
}

// The journal through the checked opener (core/regular_file.h); empty when it is missing or is
// not a regular file of at most the table ceiling (then nothing is resumed from it).
std::string readAll(const fs::path& p) {
  auto text = readRegularFile(p, kTableFileCeiling);
  return text ? std::move(*text) : std::string();
}

// Each complete line of the journal; a torn last line (no '\n') is dropped.
void readJournal(const fs::path& p, std::map<uint64_t, TileRecord>& done) {
  const std::string text = readAll(p);
  size_t start = 0;
  for (size_t nl = text.find('\n'); nl != std::string::npos; start = nl + 1, nl = text.find('\n', start)) {
    geo::TileId id;
    int e = 0, i = 0, n = 0, l = 0;
    TileRecord r;
    unsigned long long bytes = 0;
    const std::string line = text.substr(start, nl - start);
    if (std::sscanf(line.c_str(), "%d %d %d %d %d %d %d %f %f %llu", &id.z, &id.x, &id.y, &e, &i, &n, &l, &r.minH,
                    &r.maxH, &bytes) != 10)
      continue;
    r.elevation = e != 0;
    r.imagery = i != 0;
    r.ndvi = n != 0;
    r.landcover = l != 0;
    r.bytes = bytes;
    done[key(id)] = r;
  }
}

// Files a killed writer left half-done under their temporary names (core/atomic_file.h's
// "NAME.tmp-PID-N"): never renamed into place, so never part of the dataset.
void removeTemporaries(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> stray;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(".tmp-") != std::string::npos) stray.push_back(it->path());
  }
  for (const auto& p : stray) fs::remove_all(p, ec);
}

}  // namespace

fs::path importLockFileFor(const fs::path& out) {
  fs::path abs = fs::absolute(out).lexically_normal();
  if (abs.filename().empty()) abs = abs.parent_path();
  return abs.parent_path() / ("." + abs.filename().string() + ".lock");
}

Result<FileLock> lockImportOutput(const fs::path& out) {
  const fs::path lockFile = importLockFileFor(out);
  std::error_code ec;
  // The user's mistake (a file where a folder of --out should be) before any I/O error.
  fs::path p = lockFile.parent_path();
  while (!p.empty() && !fs::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  if (!fs::is_directory(p, ec))
    return makeError(ErrorKind::InvalidInput, concat("--out ", out, " cannot be created: ", p, " is not a directory"));
  fs::create_directories(lockFile.parent_path(), ec);
  if (ec) return makeError(ErrorKind::Io, concat("cannot create ", lockFile.parent_path(), ": ", ec.message()));
  return FileLock::acquire(lockFile, concat("--out ", out));
}

fs::path partialDirFor(const fs::path& out) {
  fs::path abs = fs::absolute(out).lexically_normal();
  if (abs.filename().empty()) abs = abs.parent_path();
  return abs.parent_path() / ("." + abs.filename().string() + ".partial");
}

Result<ImportJournal> ImportJournal::open(const fs::path& out, const std::string& fingerprint, bool resume) {
  ImportJournal j;
  j.dir_ = partialDirFor(out);
  std::error_code ec;
  const fs::path stamp = j.dir_ / "import.json", journal = j.dir_ / "journal.txt";
  if (resume && fs::exists(stamp, ec)) {
    if (readAll(stamp) != fingerprint)
      return makeError(ErrorKind::InvalidInput,
                       concat("--resume: ", j.dir_, " belongs to an import of other inputs or options; run it "
                                                    "again with those, or without --resume to start afresh"));
    readJournal(journal, j.done_);
    removeTemporaries(j.dir_);
  } else {
    fs::remove_all(j.dir_, ec);
    fs::create_directories(j.dir_, ec);
    if (ec) return makeError(ErrorKind::Io, concat("cannot create ", j.dir_, ": ", ec.message()));
    if (auto s = writeTextAtomically(stamp, fingerprint); !s)
      return s.error();
  }
  j.file_ = std::fopen(journal.c_str(), "ab");
  if (!j.file_) return makeError(ErrorKind::Io, concat("cannot open ", journal, " for writing: ", ioReason(errno)));
  return j;
}

ImportJournal::ImportJournal(ImportJournal&& o) noexcept
    : dir_(std::move(o.dir_)), done_(std::move(o.done_)), file_(o.file_) {
  o.file_ = nullptr;
}

ImportJournal::~ImportJournal() {
  if (file_) std::fclose(file_);
}

const TileRecord* ImportJournal::done(const geo::TileId& id) const {
  const auto it = done_.find(key(id));
  return it == done_.end() ? nullptr : &it->second;
}

Status ImportJournal::record(const geo::TileId& id, const TileRecord& r) {
  char line[160];
  const int n = std::snprintf(line, sizeof(line), "%d %d %d %d %d %d %d %.9g %.9g %" PRIu64 "\n", id.z, id.x, id.y,
                              r.elevation ? 1 : 0, r.imagery ? 1 : 0, r.ndvi ? 1 : 0, r.landcover ? 1 : 0, r.minH,
                              r.maxH, r.bytes);
  std::lock_guard lock(mutex_);
  if (std::fwrite(line, 1, static_cast<size_t>(n), file_) != static_cast<size_t>(n) || std::fflush(file_) != 0)
    return makeError(ErrorKind::Io, concat("cannot append to ", dir_ / "journal.txt", ": ", ioReason(errno)));
  return {};
}

Status ImportJournal::complete(const fs::path& out) {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  fs::remove(dir_ / "journal.txt", ec);
  fs::remove(dir_ / "import.json", ec);
  if (fs::exists(out, ec) && fs::is_directory(out, ec) && fs::is_empty(out, ec)) fs::remove(out, ec);
  if (Status s = syncDirectoryTree(dir_, out); !s) return s;
  fs::rename(dir_, out, ec);
  if (ec) return makeError(ErrorKind::Io, concat("cannot rename ", dir_, " to ", out, ": ", ec.message()));
  return syncPath(out.parent_path().empty() ? fs::path(".") : fs::absolute(out).parent_path(), out);
}

void ImportJournal::discard() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

}  // namespace vegstream::datasets
