#pragma once
// DiskTileCache: the HTTP source's optional on-disk copy of the tiles it fetched, so that a
// second flight over the same area (or a restart) does not fetch them again.
//
// Layout: DIR/<key, sanitised>, one file per key, where the key is the URL without its scheme
// ("127.0.0.1:8080/zion/elevation/12/758/1608.png"). Each '/'-separated segment becomes a
// directory level; bytes outside [A-Za-z0-9.-] are written as "_XX" (hex), so every key maps to
// one file name and no key can leave DIR (".." becomes "_2E_2E").
//
// Files are written atomically (core/atomic_file.h): a reader never sees half a tile, even
// after a crash. The byte budget holds after every put(): least-recently-used files (by the use
// time this class records; a file's modification time carries it across restarts) are removed
// first. A file larger than the whole budget is not stored.
//
// Thread-safe: every member may be called from any thread.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/log.h"
#include "core/result.h"

namespace vegstream::streaming {

struct DiskCacheStats {
  uint64_t files = 0;
  uint64_t bytes = 0;
  uint64_t hits = 0;
  uint64_t misses = 0;
  uint64_t evictions = 0;
};

class DiskTileCache {
 public:
  // Creates DIR if needed and takes in the files already there (oldest first evicted, by their
  // modification times). Io error when DIR cannot be created or listed. `name` is what the
  // messages call it (the store holds any keyed bytes: render/impostor_atlas_cache.h keeps the
  // tree impostors in one).
  static Result<std::unique_ptr<DiskTileCache>> open(const std::filesystem::path& dir, uint64_t budgetBytes, Logger log,
                                                     std::string name = "tile cache");

  // The cached bytes of `key`, or nullopt (a miss, or a file that can no longer be read).
  std::optional<std::vector<uint8_t>> get(const std::string& key);

  // Stores `bytes` under `key` (replacing an older copy), then evicts down to the budget.
  Status put(const std::string& key, std::span<const uint8_t> bytes);

  // Removes the copy of `key`, if any (a cached tile that no longer passes the tile check).
  void remove(const std::string& key);

  DiskCacheStats stats() const;
  uint64_t budgetBytes() const { return budgetBytes_; }
  const std::filesystem::path& dir() const { return dir_; }

  // The file of `key` relative to DIR (the sanitising rule above).
  static std::filesystem::path relativeFileFor(const std::string& key);

 private:
  struct Entry {
    uint64_t bytes = 0;
    uint64_t lastUse = 0;  // a tick of useClock_; larger is more recent
  };
  DiskTileCache(std::filesystem::path dir, uint64_t budgetBytes, Logger log, std::string name);
  void touchLocked(const std::filesystem::path& rel, Entry& e);
  void evictLocked(const std::filesystem::path& keep);
  void forgetLocked(const std::filesystem::path& rel);

  const std::filesystem::path dir_;
  const uint64_t budgetBytes_;
  Logger log_;
  const std::string name_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Entry> entries_;  // by relative file path (generic string)
  std::map<uint64_t, std::string> byUse_;           // lastUse → relative file path
  uint64_t useClock_ = 0;
  DiskCacheStats stats_;
};

}  // namespace vegstream::streaming
