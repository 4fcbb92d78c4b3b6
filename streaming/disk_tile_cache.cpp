// DiskTileCache (disk_tile_cache.h).

#include "streaming/disk_tile_cache.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <tuple>

#include "core/atomic_file.h"
#include "core/regular_file.h"
#include "streaming/escaped_bytes.h"

namespace vegstream::streaming {
namespace fs = std::filesystem;

namespace {

constexpr const char* kTempMarker = ".tmp-";  // core/atomic_file.cpp's temporary names

bool keptAsIs(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-';
}

std::string sanitiseSegment(std::string_view segment) {
  const bool dotsOnly = std::all_of(segment.begin(), segment.end(), [](char c) { return c == '.'; });
  return escapeBytes(segment, '_', [dotsOnly](char c) { return keptAsIs(c) && !dotsOnly; });
}

// Through the checked opener (core/regular_file.h): anything but a regular tile-sized file is a
// miss, never a hang or an endless read.
std::optional<std::vector<uint8_t>> readWholeFile(const fs::path& file) {
  auto bytes = readRegularFileBytes(file, kTileFileCeiling);
  if (!bytes) return std::nullopt;
  return std::move(*bytes);
}

}  // namespace

fs::path DiskTileCache::relativeFileFor(const std::string& key) {
  fs::path rel;
  size_t begin = 0;
  while (begin <= key.size()) {
    size_t end = key.find('/', begin);
    if (end == std::string::npos) end = key.size();
    // Empty segments ("a//b", a trailing '/') still name something: keep them distinct.
    const std::string_view segment(key.data() + begin, end - begin);
    rel /= segment.empty() ? std::string("_") : sanitiseSegment(segment);
    begin = end + 1;
  }
  return rel;
}

DiskTileCache::DiskTileCache(fs::path dir, uint64_t budgetBytes, Logger log, std::string name)
    : dir_(std::move(dir)), budgetBytes_(budgetBytes), log_(std::move(log)), name_(std::move(name)) {}

Result<std::unique_ptr<DiskTileCache>> DiskTileCache::open(const fs::path& dir, uint64_t budgetBytes, Logger log,
                                                           std::string name) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    return makeError(ErrorKind::Io, "cannot create the " + name + " directory " + dir.string() + ": " + ec.message());
  std::unique_ptr<DiskTileCache> cache(new DiskTileCache(dir, budgetBytes, std::move(log), name));

  // Existing files, oldest modification first, become the least recently used.
  std::vector<std::tuple<fs::file_time_type, std::string, uint64_t>> found;
  const auto staleTemp = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const auto mtime = it->last_write_time(ec);
    if (ec) continue;
    if (it->path().filename().string().find(kTempMarker) != std::string::npos) {
      // A writer died half-way (a live one renames within milliseconds).
      if (mtime < staleTemp) fs::remove(it->path(), ec);
      continue;
    }
    found.emplace_back(mtime, fs::relative(it->path(), dir).generic_string(), it->file_size(ec));
  }
  if (ec)
    return makeError(ErrorKind::Io, "cannot list the " + name + " directory " + dir.string() + ": " + ec.message());
  std::sort(found.begin(), found.end());

  std::lock_guard lock(cache->mutex_);
  for (auto& [mtime, rel, bytes] : found) {
    const uint64_t tick = ++cache->useClock_;
    cache->entries_[rel] = Entry{bytes, tick};
    cache->byUse_[tick] = rel;
    cache->stats_.bytes += bytes;
  }
  cache->evictLocked({});
  return cache;
}

void DiskTileCache::touchLocked(const fs::path& rel, Entry& e) {
  byUse_.erase(e.lastUse);
  e.lastUse = ++useClock_;
  byUse_[e.lastUse] = rel.generic_string();
}

void DiskTileCache::forgetLocked(const fs::path& rel) {
  auto it = entries_.find(rel.generic_string());
  if (it == entries_.end()) return;
  byUse_.erase(it->second.lastUse);
  stats_.bytes -= it->second.bytes;
  entries_.erase(it);
}

void DiskTileCache::evictLocked(const fs::path& keep) {
  const std::string keepKey = keep.generic_string();
  auto it = byUse_.begin();
  while (stats_.bytes > budgetBytes_ && it != byUse_.end()) {
    if (it->second == keepKey) {
      ++it;
      continue;
    }
    const std::string rel = it->second;
    ++it;  // forgetLocked erases the current element
    std::error_code ec;
    fs::remove(dir_ / rel, ec);
    if (ec && log_) log_->warn("{}: cannot remove {}: {}", name_, (dir_ / rel).string(), ec.message());
    forgetLocked(rel);
    ++stats_.evictions;
  }
  stats_.files = entries_.size();
}

std::optional<std::vector<uint8_t>> DiskTileCache::get(const std::string& key) {
  const fs::path rel = relativeFileFor(key);
  {
    std::lock_guard lock(mutex_);
    if (entries_.find(rel.generic_string()) == entries_.end()) {
      ++stats_.misses;
      return std::nullopt;
    }
  }
  // Read outside the lock; an eviction racing with us makes this a miss, never a wrong answer
  // (files are replaced by rename, so a reader sees the old or the new copy, whole).
  auto bytes = readWholeFile(dir_ / rel);
  std::lock_guard lock(mutex_);
  auto it = entries_.find(rel.generic_string());
  if (!bytes || it == entries_.end()) {
    if (!bytes) forgetLocked(rel);
    stats_.files = entries_.size();
    ++stats_.misses;
    return std::nullopt;
  }
  touchLocked(rel, it->second);
  std::error_code ec;
  fs::last_write_time(dir_ / rel, fs::file_time_type::clock::now(), ec);  // carries the use across restarts
  ++stats_.hits;
  return bytes;
}

Status DiskTileCache::put(const std::string& key, std::span<const uint8_t> bytes) {
  if (bytes.size() > budgetBytes_) return {};  // would evict everything and itself
  const fs::path rel = relativeFileFor(key);
  const fs::path file = dir_ / rel;
  Status written = writeBytesAtomically(file, bytes);
  if (!written) return written;
  std::lock_guard lock(mutex_);
  forgetLocked(rel);
  const uint64_t tick = ++useClock_;
  entries_[rel.generic_string()] = Entry{bytes.size(), tick};
  byUse_[tick] = rel.generic_string();
  stats_.bytes += bytes.size();
  evictLocked(rel);
  return {};
}

void DiskTileCache::remove(const std::string& key) {
  const fs::path rel = relativeFileFor(key);
  std::lock_guard lock(mutex_);
  std::error_code ec;
  fs::remove(dir_ / rel, ec);
  if (ec && log_) log_->warn("{}: cannot remove {}: {}", name_, (dir_ / rel).string(), ec.message());
  if (entries_.count(rel.generic_string()) != 0) ++stats_.evictions;
  forgetLocked(rel);
  stats_.files = entries_.size();
}

DiskCacheStats DiskTileCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace vegstream::streaming
