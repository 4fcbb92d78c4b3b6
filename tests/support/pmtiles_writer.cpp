// The tests' PMTiles v3 writer (pmtiles_writer.h).

#include "tests/support/pmtiles_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>

#include <zlib.h>

namespace vegstream::testing {
namespace {

struct Entry {
  uint64_t tileId, offset, length, runLength;
};

void varint(std::vector<uint8_t>& out, uint64_t v) {
  do {
    uint8_t b = v & 0x7f;
    v >>= 7;
    out.push_back(v ? (b | 0x80) : b);
  } while (v);
}

void le(std::vector<uint8_t>& out, size_t at, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

std::vector<uint8_t> directory(const std::vector<Entry>& e, bool gzip) {
  std::vector<uint8_t> out;
  varint(out, e.size());
  for (size_t i = 0; i < e.size(); ++i) varint(out, e[i].tileId - (i ? e[i - 1].tileId : 0));
  for (const auto& x : e) varint(out, x.runLength);
  for (const auto& x : e) varint(out, x.length);
  for (size_t i = 0; i < e.size(); ++i)
    varint(out, i > 0 && e[i].offset == e[i - 1].offset + e[i - 1].length ? 0 : e[i].offset + 1);
  return gzip ? gzipBytes(out) : out;
}

}  // namespace

std::vector<uint8_t> gzipBytes(const std::vector<uint8_t>& bytes) {
  z_stream zs{};
  deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::vector<uint8_t> out(deflateBound(&zs, bytes.size()) + 32);
  zs.next_in = const_cast<Bytef*>(bytes.data());
  zs.avail_in = static_cast<uInt>(bytes.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

// Hilbert d of (x, y) on the 2^z square (Wikipedia's xy2d, rotating the whole square), plus the
// number of tiles of all lower zooms.
uint64_t referenceTileId(const geo::TileId& id) {
  uint64_t below = 0;
  for (int t = 0; t < id.z; ++t) below += uint64_t{1} << (2 * t);
  const int64_t n = int64_t{1} << id.z;
  int64_t x = id.x, y = id.y;
  uint64_t d = 0;
  for (int64_t s = n / 2; s > 0; s /= 2) {
    const int64_t rx = (x & s) > 0, ry = (y & s) > 0;
    d += static_cast<uint64_t>(s) * static_cast<uint64_t>(s) * static_cast<uint64_t>((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) x = n - 1 - x, y = n - 1 - y;
      std::swap(x, y);
    }
  }
  return below + d;
}

namespace {

struct Sections {
  std::vector<Entry> entries;
  std::vector<uint8_t> root, metadata, leaves, data;
  uint64_t contents = 0;
};

// Tile data (deduplicated) and the entries pointing into it, runs merged.
void addTiles(const std::map<geo::TileId, std::vector<uint8_t>>& tiles, bool gzipTiles, Sections& out) {
  std::vector<std::pair<uint64_t, const std::vector<uint8_t>*>> byId;
  for (const auto& [id, bytes] : tiles) byId.emplace_back(referenceTileId(id), &bytes);
  std::sort(byId.begin(), byId.end());
  std::map<std::string, uint64_t> offsetOf;  // by content
  for (const auto& [tileId, raw] : byId) {
    const std::vector<uint8_t> bytes = gzipTiles ? gzipBytes(*raw) : *raw;
    const std::string key(bytes.begin(), bytes.end());
    auto found = offsetOf.find(key);
    Entry* last = out.entries.empty() ? nullptr : &out.entries.back();
    if (last && found != offsetOf.end() && last->offset == found->second && last->tileId + last->runLength == tileId) {
      ++last->runLength;
      continue;
    }
    if (found == offsetOf.end()) {
      found = offsetOf.emplace(key, out.data.size()).first;
      out.data.insert(out.data.end(), bytes.begin(), bytes.end());
    }
    out.entries.push_back({tileId, found->second, bytes.size(), 1});
  }
  out.contents = offsetOf.size();
}

void addDirectories(const PmtilesWriteOptions& o, Sections& out) {
  const auto& entries = out.entries;
  if (o.maxRootEntries == 0 || entries.size() <= o.maxRootEntries) {
    out.root = directory(entries, o.gzipDirectories);
    return;
  }
  std::vector<Entry> rootEntries;
  for (size_t i = 0; i < entries.size(); i += o.maxRootEntries) {
    const auto from = entries.begin() + static_cast<std::ptrdiff_t>(i);
    const std::vector<Entry> part(from, from + static_cast<std::ptrdiff_t>(std::min(o.maxRootEntries, entries.size() - i)));
    const std::vector<uint8_t> leaf = directory(part, o.gzipDirectories);
    rootEntries.push_back({part.front().tileId, out.leaves.size(), leaf.size(), 0});
    out.leaves.insert(out.leaves.end(), leaf.begin(), leaf.end());
  }
  out.root = directory(rootEntries, o.gzipDirectories);
}

uint64_t e7(double deg) {
  return static_cast<uint64_t>(static_cast<uint32_t>(static_cast<int32_t>(std::lround(deg * 1e7))));
}

std::vector<uint8_t> header(const std::map<geo::TileId, std::vector<uint8_t>>& tiles, const PmtilesWriteOptions& o,
                            const Sections& x) {
  std::vector<uint8_t> out(127, 0);
  std::memcpy(out.data(), "PMTiles", 7);
  out[7] = 3;
  const uint64_t rootOff = 127, metaOff = rootOff + x.root.size(), leafOff = metaOff + x.metadata.size(),
                 dataOff = leafOff + x.leaves.size();
  le(out, 8, rootOff, 8), le(out, 16, x.root.size(), 8), le(out, 24, metaOff, 8), le(out, 32, x.metadata.size(), 8);
  le(out, 40, leafOff, 8), le(out, 48, x.leaves.size(), 8), le(out, 56, dataOff, 8), le(out, 64, x.data.size(), 8);
  le(out, 72, tiles.size(), 8), le(out, 80, x.entries.size(), 8), le(out, 88, x.contents, 8);
  out[96] = 1;
  out[97] = o.gzipDirectories ? 2 : 1;
  out[98] = o.gzipTiles ? 2 : 1;
  out[99] = o.tileType;
  int minZ = 99, maxZ = 0;
  double w = 180, s = 90, e = -180, n = -90;
  for (const auto& [id, bytes] : tiles) {
    minZ = std::min(minZ, id.z), maxZ = std::max(maxZ, id.z);
    const auto b = geo::tileBoundsLonLat(id);
    w = std::min(w, b.westDeg), s = std::min(s, b.southDeg), e = std::max(e, b.eastDeg), n = std::max(n, b.northDeg);
  }
  out[100] = static_cast<uint8_t>(minZ), out[101] = static_cast<uint8_t>(maxZ);
  le(out, 102, e7(w), 4), le(out, 106, e7(s), 4), le(out, 110, e7(e), 4), le(out, 114, e7(n), 4);
  out[118] = static_cast<uint8_t>(maxZ);
  le(out, 119, e7((w + e) / 2), 4), le(out, 123, e7((s + n) / 2), 4);
  return out;
}

}  // namespace

std::vector<uint8_t> buildPmtiles(const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                                  const PmtilesWriteOptions& o) {
  Sections x;
  addTiles(tiles, o.gzipTiles, x);
  addDirectories(o, x);
  x.metadata = o.gzipDirectories ? gzipBytes({'{', '}'}) : std::vector<uint8_t>{'{', '}'};
  std::vector<uint8_t> out = header(tiles, o, x);
  for (const std::vector<uint8_t>* part : {&x.root, &x.metadata, &x.leaves, &x.data})
    out.insert(out.end(), part->begin(), part->end());
  return out;
}

void writePmtiles(const std::filesystem::path& path, const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                  const PmtilesWriteOptions& options) {
  const auto bytes = buildPmtiles(tiles, options);
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace vegstream::testing
