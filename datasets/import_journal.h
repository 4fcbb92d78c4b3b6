#pragma once
// Where an import works, and what it has done, so that `import --resume` continues one that was
// killed (SIGKILL, power loss) instead of starting again.
//
// The import writes into `.NAME.partial/` beside `--out` (never a dataset: dataset.json is
// written last, and the directory is renamed to --out only then). Inside, `import.json` holds
// the fingerprint of the inputs and options, and `journal.txt` one line per finished max-zoom
// tile, appended once all of the tile's files are renamed into place:
//   "z x y E I N minH maxH bytes\n"   (E, I, N: 0/1 for elevation, imagery, NDVI written)
// A torn last line (a kill mid-write) is ignored, so its tile is made again; files a killed
// writer left under temporary names are removed on --resume.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

#include "core/file_lock.h"
#include "core/result.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

struct TileRecord {
  bool elevation = false, imagery = false, ndvi = false, landcover = false;
  float minH = 0.0f, maxH = 0.0f;
  uint64_t bytes = 0;
};

std::filesystem::path partialDirFor(const std::filesystem::path& out);

// One import at a time per --out: `.NAME.lock` beside `out` (core/file_lock.h), held for the
// whole import. A second import to the same --out is refused (InvalidInput naming it and the
// holder's PID) instead of removing or resuming the first one's partial directory. The kernel
// drops the lock of a killed import, so the next run proceeds and cleans what that one left.
std::filesystem::path importLockFileFor(const std::filesystem::path& out);
Result<FileLock> lockImportOutput(const std::filesystem::path& out);

class ImportJournal {
 public:
  // Makes the partial directory for `out`. resume: an existing one whose fingerprint equals
  // `fingerprint` is continued (its journal read); one with another fingerprint is an error
  // naming it. Without resume an existing one is removed first.
  static Result<ImportJournal> open(const std::filesystem::path& out, const std::string& fingerprint, bool resume);
  ~ImportJournal();
  ImportJournal(ImportJournal&&) noexcept;
  ImportJournal(const ImportJournal&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  // The record of a tile the journal says is finished.
  const TileRecord* done(const geo::TileId& id) const;
  size_t doneCount() const { return done_.size(); }
  // Appends a finished tile (thread-safe; flushed to the file before returning).
  Status record(const geo::TileId& id, const TileRecord& r);
  // Removes import.json and journal.txt, then renames the directory to `out`.
  Status complete(const std::filesystem::path& out);
  // Removes the directory (a failure or an interruption: nothing is left).
  void discard();

 private:
  ImportJournal() = default;
  std::filesystem::path dir_;
  std::map<uint64_t, TileRecord> done_;
  std::FILE* file_ = nullptr;
  std::mutex mutex_;
};

}  // namespace vegstream::datasets
