// PMTiles v3 archives as a tile source (xyz_source.h), by local path (pread) or by URL (HTTP
// Range requests through http_fetch.h). Spec: https://github.com/protomaps/PMTiles/blob/main/spec/v3/spec.md
//
// Opening reads the first 16 KiB (header + root directory, as the spec places them) in one
// read. A tile is found by descending from the root through leaf directories (at most
// kMaxDepth levels, so a directory that points at itself ends); directories read once are kept
// (by offset) for the other tiles. Listing one zoom walks only the entries whose tile ids lie
// in that zoom's id range [first(z), first(z+1)), descending into the leaves that overlap it.
// Tile data compressed with gzip is inflated; brotli / zstd are refused.

#include <fcntl.h>
#include <unistd.h>

#include <map>
#include <mutex>

#include "datasets/message.h"
#include "datasets/pmtiles_format.h"
#include "datasets/tile_template.h"
#include "datasets/xyz_source.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

constexpr int kMaxDepth = 4;
constexpr size_t kMaxDirectoryVisits = 1u << 16;  // per listing: leaves shared by many entries cannot explode it
constexpr uint64_t kMaxDirectoryBytes = 64ull << 20;
constexpr uint64_t kMaxTileBytes = 64ull << 20;

// Bytes [offset, offset + length) of the archive; fewer only at its end.
class ByteReader {
 public:
  virtual ~ByteReader() = default;
  virtual Result<std::vector<uint8_t>> read(uint64_t offset, uint64_t length) const = 0;
  virtual std::optional<uint64_t> size() const = 0;
};

class FileReader final : public ByteReader {
 public:
  FileReader(std::string name, int fd, uint64_t size) : name_(std::move(name)), fd_(fd), size_(size) {}
  ~FileReader() override { ::close(fd_); }
  Result<std::vector<uint8_t>> read(uint64_t offset, uint64_t length) const override {
    if (offset >= size_) return std::vector<uint8_t>();
    std::vector<uint8_t> out(std::min(length, size_ - offset));
    size_t done = 0;
    while (done < out.size()) {
      const ssize_t n = ::pread(fd_, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
      if (n <= 0) return makeError(ErrorKind::Io, concat("cannot read '", name_, "' at byte ", offset + done));
      done += static_cast<size_t>(n);
    }
    return out;
  }
  std::optional<uint64_t> size() const override { return size_; }

 private:
  std::string name_;
  int fd_;
  uint64_t size_;
};

class HttpReader final : public ByteReader {
 public:
  HttpReader(std::string url, const HttpFetchOptions& o) : url_(std::move(url)), http_(o) {}
  Result<std::vector<uint8_t>> read(uint64_t offset, uint64_t length) const override {
    auto r = http_.get(url_, ByteRange{offset, length});
    if (!r) return r.error();
    if (!*r) return makeError(ErrorKind::NotFound, concat("PMTiles archive '", url_, "' does not exist (HTTP 404)"));
    return std::move(**r);
  }
  std::optional<uint64_t> size() const override { return std::nullopt; }

 private:
  std::string url_;
  HttpFetcher http_;
};

class PmtilesSource final : public XyzSource {
 public:
  PmtilesSource(std::string name, std::unique_ptr<ByteReader> reader)
      : XyzSource(std::move(name)), reader_(std::move(reader)) {}
  const char* kind() const override { return "PMTiles"; }
  bool listsTiles() const override { return true; }
  bool remote() const override { return !reader_->size().has_value(); }
  XyzSourceExtent extent() const override;
  Result<std::vector<geo::TileId>> tilesAt(int z, const std::optional<geo::GeoBounds>& bounds,
                                           uint64_t maxTiles) override;
  Result<std::optional<std::vector<uint8_t>>> read(const geo::TileId& id) override;
  std::string tileName(const geo::TileId& id) const override { return concat(name(), " tile ", geo::toString(id)); }
  Status open();

 private:
  using Directory = std::shared_ptr<const std::vector<PmtilesEntry>>;
  Result<Directory> directory(uint64_t absoluteOffset, uint64_t length);
  Result<std::optional<PmtilesEntry>> locate(const geo::TileId& id);
  Status walk(const Directory& dir, uint64_t lo, uint64_t hi, int depth, std::vector<uint64_t>& ids, uint64_t max,
              size_t& visits);
  Error bad(const std::string& problem) const {
    return makeError(ErrorKind::InvalidInput, concat("'", name(), "' is not a valid PMTiles v3 archive: ", problem));
  }

  std::unique_ptr<ByteReader> reader_;
  PmtilesHeader header_;
  Directory root_;
  std::mutex mutex_;
  std::map<uint64_t, Directory> leaves_;  // by absolute offset
};

XyzSourceExtent PmtilesSource::extent() const {
  XyzSourceExtent e;
  e.minZoom = header_.minZoom, e.maxZoom = header_.maxZoom;
  const geo::GeoBounds b{header_.minLonE7 / 1e7, header_.minLatE7 / 1e7, header_.maxLonE7 / 1e7,
                         header_.maxLatE7 / 1e7};
  if (b.southDeg < b.northDeg && b.westDeg < b.eastDeg && b.southDeg >= -90 && b.northDeg <= 90) e.bounds = b;
  return e;
}

Status PmtilesSource::open() {
  auto first = reader_->read(0, kPmtilesFirstReadBytes);
  if (!first) return first.error();
  auto h = decodePmtilesHeader(*first, name(), reader_->size());
  if (!h) return h.error();
  header_ = *h;
  if (header_.tileType == PmtilesTileType::Mvt || header_.tileType == PmtilesTileType::Avif)
    return makeError(ErrorKind::Unsupported,
                     concat("'", name(), "' holds ", header_.tileType == PmtilesTileType::Mvt ? "vector (MVT)" : "AVIF",
                            " tiles; vegstream imports PNG, JPEG and WebP tiles"));
  if (header_.tileCompression != PmtilesCompression::None && header_.tileCompression != PmtilesCompression::Gzip &&
      header_.tileCompression != PmtilesCompression::Unknown)
    return makeError(ErrorKind::Unsupported, concat("'", name(), "' compresses its tiles with method ",
                                                    static_cast<int>(header_.tileCompression),
                                                    "; vegstream reads uncompressed and gzip tiles"));
  if (header_.rootLength > kMaxDirectoryBytes) return bad("root directory too large");
  Result<std::vector<PmtilesEntry>> entries = bad("no root directory");
  if (header_.rootOffset + header_.rootLength <= first->size()) {
    entries = decodePmtilesDirectory(std::span(*first).subspan(header_.rootOffset, header_.rootLength),
                                     header_.internalCompression, name());
  } else {
    auto bytes = reader_->read(header_.rootOffset, header_.rootLength);
    if (!bytes) return bytes.error();
    if (bytes->size() != header_.rootLength) return bad("truncated root directory");
    entries = decodePmtilesDirectory(*bytes, header_.internalCompression, name());
  }
  if (!entries) return entries.error();
  root_ = std::make_shared<const std::vector<PmtilesEntry>>(std::move(*entries));
  return {};
}

Result<PmtilesSource::Directory> PmtilesSource::directory(uint64_t offset, uint64_t length) {
  {
    std::lock_guard lock(mutex_);
    if (auto it = leaves_.find(offset); it != leaves_.end()) return it->second;
  }
  if (length > kMaxDirectoryBytes) return bad(concat("leaf directory of ", length, " bytes"));
  auto bytes = reader_->read(offset, length);
  if (!bytes) return bytes.error();
  if (bytes->size() != length) return bad("truncated leaf directory");
  auto entries = decodePmtilesDirectory(*bytes, header_.internalCompression, name());
  if (!entries) return entries.error();
  auto dir = std::make_shared<const std::vector<PmtilesEntry>>(std::move(*entries));
  std::lock_guard lock(mutex_);
  return leaves_.emplace(offset, dir).first->second;
}

// The tile entry for `id` (offset relative to the tile data), found through the leaves.
Result<std::optional<PmtilesEntry>> PmtilesSource::locate(const geo::TileId& id) {
  const uint64_t tileId = pmtilesTileId(id);
  Directory dir = root_;
  for (int depth = 0; depth <= kMaxDepth; ++depth) {
    const auto e = findPmtilesEntry(*dir, tileId);
    if (!e || e->runLength > 0) return e;
    if (e->offset > header_.leafLength || e->length > header_.leafLength - e->offset)
      return bad("a leaf directory lies outside the leaf section");
    auto leaf = directory(header_.leafOffset + e->offset, e->length);
    if (!leaf) return leaf.error();
    dir = *leaf;
  }
  return bad(concat("leaf directories nested deeper than ", kMaxDepth, " levels"));
}

Result<std::optional<std::vector<uint8_t>>> PmtilesSource::read(const geo::TileId& id) {
  auto e = locate(id);
  if (!e) return e.error();
  if (!*e) return std::optional<std::vector<uint8_t>>();
  const PmtilesEntry& t = **e;
  if (t.offset > header_.tileDataLength || t.length > header_.tileDataLength - t.offset)
    return bad(concat("tile ", geo::toString(id), " lies outside the tile data section"));
  if (t.length > kMaxTileBytes) return bad(concat("tile ", geo::toString(id), " has ", t.length, " bytes"));
  auto bytes = reader_->read(header_.tileDataOffset + t.offset, t.length);
  if (!bytes) return bytes.error();
  if (bytes->size() != t.length) return bad(concat("tile ", geo::toString(id), " is truncated"));
  if (header_.tileCompression == PmtilesCompression::Gzip) {
    auto inflated = gunzip(*bytes, tileName(id), kMaxTileBytes);
    if (!inflated) return inflated.error();
    return std::optional<std::vector<uint8_t>>(std::move(*inflated));
  }
  return std::optional<std::vector<uint8_t>>(std::move(*bytes));
}

// The tile ids in [lo, hi) that `dir` (and its leaves) address, appended in order.
Status PmtilesSource::walk(const Directory& dir, uint64_t lo, uint64_t hi, int depth, std::vector<uint64_t>& ids,
                           uint64_t max, size_t& visits) {
  if (depth > kMaxDepth) return bad(concat("leaf directories nested deeper than ", kMaxDepth, " levels"));
  if (++visits > kMaxDirectoryVisits) return bad(concat("more than ", kMaxDirectoryVisits, " directory visits"));
  for (size_t i = 0; i < dir->size(); ++i) {
    const PmtilesEntry& e = (*dir)[i];
    const uint64_t end = e.runLength > 0 ? e.tileId + e.runLength : i + 1 < dir->size() ? (*dir)[i + 1].tileId : hi;
    if (end <= lo || e.tileId >= hi) continue;
    if (e.runLength == 0) {
      if (e.offset > header_.leafLength || e.length > header_.leafLength - e.offset)
        return bad("a leaf directory lies outside the leaf section");
      auto leaf = directory(header_.leafOffset + e.offset, e.length);
      if (!leaf) return leaf.error();
      if (auto s = walk(*leaf, lo, hi, depth + 1, ids, max, visits); !s) return s;
      continue;
    }
    for (uint64_t t = std::max(e.tileId, lo); t < std::min(end, hi); ++t) {
      if (ids.size() >= max)
        return makeError(ErrorKind::InvalidInput,
                         concat("'", name(), "' has more than ", max, " tiles at one zoom (a lower --max-zoom)"));
      ids.push_back(t);
    }
  }
  return {};
}

Result<std::vector<geo::TileId>> PmtilesSource::tilesAt(int z, const std::optional<geo::GeoBounds>& bounds,
                                                        uint64_t maxTiles) {
  std::vector<geo::TileId> out;
  if (bounds) {  // look the tiles over the bounds up, when there are not too many of them
    uint64_t count = 0;
    for (const auto& r : geo::tileRangesCovering(*bounds, z)) count += static_cast<uint64_t>(r.count());
    if (count <= maxTiles) {
      for (const geo::TileId& id : geo::tilesCovering(*bounds, z)) {
        auto e = locate(id);  // descends through the leaves, which are read once and kept
        if (!e) return e.error();
        if (*e) out.push_back(id);
      }
      std::sort(out.begin(), out.end());
      return out;
    }
  }
  std::vector<uint64_t> ids;
  size_t visits = 0;
  if (auto s = walk(root_, pmtilesFirstId(z), pmtilesFirstId(z + 1), 0, ids, maxTiles, visits); !s) return s.error();
  const auto ranges = bounds ? geo::tileRangesCovering(*bounds, z) : std::vector<geo::TileRange>{};
  for (uint64_t t : ids) {
    const geo::TileId id = pmtilesTileZxy(t);
    if (bounds && std::none_of(ranges.begin(), ranges.end(), [&](const auto& r) { return r.contains(id); })) continue;
    out.push_back(id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

Result<std::unique_ptr<XyzSource>> openPmtilesSource(const std::string& pathOrUrl, const HttpFetchOptions& http) {
  std::unique_ptr<ByteReader> reader;
  if (looksLikeHttpUrl(pathOrUrl)) {
    reader = std::make_unique<HttpReader>(pathOrUrl, http);
  } else {
    if (Status s = checkArchiveFile(pathOrUrl, concat("PMTiles archive '", pathOrUrl, "'")); !s) return s.error();
    const int fd = ::open(pathOrUrl.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return makeError(ErrorKind::Io, concat("cannot open PMTiles archive '", pathOrUrl, "'"));
    std::error_code ec;
    reader = std::make_unique<FileReader>(pathOrUrl, fd, fs::file_size(pathOrUrl, ec));
  }
  auto source = std::make_unique<PmtilesSource>(pathOrUrl, std::move(reader));
  if (auto s = source->open(); !s) return s.error();
  return std::unique_ptr<XyzSource>(std::move(source));
}

}  // namespace vegstream::datasets
