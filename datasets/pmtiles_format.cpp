// PMTiles v3 header, directories and tile ids (pmtiles_format.h).
// Spec: https://github.com/protomaps/PMTiles/blob/main/spec/v3/spec.md. Varints: LEB128 as in
// Protocol Buffers (7 bits per byte, least significant group first). Hilbert curve: the
// classic xy2d / d2xy (Hamilton, "Compact Hilbert Indices", 2006; as the spec's reference code).

#include "datasets/pmtiles_format.h"

#include <algorithm>
#include <cassert>
#include <cstring>

#include <zlib.h>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

Error bad(const std::string& name, const std::string& problem) {
  return makeError(ErrorKind::InvalidInput, concat("'", name, "' is not a valid PMTiles v3 archive: ", problem));
}

uint64_t le64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | p[i];
  return v;
}
int32_t le32s(const uint8_t* p) {
  const uint32_t v = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
  int32_t s;
  std::memcpy(&s, &v, 4);
  return s;
}
void put64(std::vector<uint8_t>& out, size_t at, uint64_t v) {
  for (size_t i = 0; i < 8; ++i) out[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
void put32(std::vector<uint8_t>& out, size_t at, int32_t s) {
  uint32_t v;
  std::memcpy(&v, &s, 4);
  for (size_t i = 0; i < 4; ++i) out[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

// Reads one varint at `at`; false when it runs past the end or beyond 64 bits.
bool readVarint(std::span<const uint8_t> b, size_t& at, uint64_t& v) {
  v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (at >= b.size()) return false;
    const uint8_t byte = b[at++];
    if (shift == 63 && (byte & 0x7e) != 0) return false;
    v |= uint64_t{byte & 0x7fu} << shift;
    if ((byte & 0x80) == 0) return true;
  }
  return false;
}
void writeVarint(std::vector<uint8_t>& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

bool knownCompression(uint8_t c) { return c <= 4; }

// Hilbert rotation of the sub-square of side s (only the bits below s matter afterwards).
void rotate(uint64_t s, uint64_t& x, uint64_t& y, uint64_t rx, uint64_t ry) {
  if (ry == 0) {
    if (rx == 1) {
      x = s - 1 - (x & (s - 1));
      y = s - 1 - (y & (s - 1));
    }
    std::swap(x, y);
  }
}

}  // namespace

Result<PmtilesHeader> decodePmtilesHeader(std::span<const uint8_t> b, const std::string& name,
                                          std::optional<uint64_t> fileSize) {
  if (b.size() >= 7 && std::memcmp(b.data(), "PMTiles", 7) != 0) return bad(name, "bad magic (no 'PMTiles')");
  if (b.size() < kPmtilesHeaderBytes)
    return bad(name, concat("truncated header (", b.size(), " of ", kPmtilesHeaderBytes, " bytes)"));
  if (b[7] != 3) return bad(name, concat("spec version ", int{b[7]}, "; vegstream reads version 3"));
  PmtilesHeader h;
  const uint8_t* p = b.data();
  h.rootOffset = le64(p + 8), h.rootLength = le64(p + 16);
  h.metadataOffset = le64(p + 24), h.metadataLength = le64(p + 32);
  h.leafOffset = le64(p + 40), h.leafLength = le64(p + 48);
  h.tileDataOffset = le64(p + 56), h.tileDataLength = le64(p + 64);
  h.addressedTiles = le64(p + 72), h.tileEntries = le64(p + 80), h.tileContents = le64(p + 88);
  h.clustered = p[96] == 1;
  if (!knownCompression(p[97]) || !knownCompression(p[98]) || p[99] > 5)
    return bad(name, concat("unknown compression or tile type (", int{p[97]}, ", ", int{p[98]}, ", ", int{p[99]}, ")"));
  h.internalCompression = static_cast<PmtilesCompression>(p[97]);
  h.tileCompression = static_cast<PmtilesCompression>(p[98]);
  h.tileType = static_cast<PmtilesTileType>(p[99]);
  h.minZoom = p[100], h.maxZoom = p[101];
  h.minLonE7 = le32s(p + 102), h.minLatE7 = le32s(p + 106), h.maxLonE7 = le32s(p + 110), h.maxLatE7 = le32s(p + 114);
  h.centerZoom = p[118], h.centerLonE7 = le32s(p + 119), h.centerLatE7 = le32s(p + 123);
  if (h.maxZoom > geo::kMaxTileZoom || h.minZoom > h.maxZoom)
    return bad(name, concat("zooms ", h.minZoom, " … ", h.maxZoom));
  if (h.rootLength == 0) return bad(name, "empty root directory");
  const uint64_t end = fileSize.value_or(~uint64_t{0});
  auto within = [end](uint64_t off, uint64_t len) { return off <= end && len <= end - off; };
  if (!within(h.rootOffset, h.rootLength) || !within(h.leafOffset, h.leafLength) ||
      !within(h.tileDataOffset, h.tileDataLength) || !within(h.metadataOffset, h.metadataLength))
    return bad(name, concat("a section lies beyond the end of the file (", end, " bytes)"));
  return h;
}

std::vector<uint8_t> encodePmtilesHeader(const PmtilesHeader& h) {
  std::vector<uint8_t> out(kPmtilesHeaderBytes, 0);
  std::memcpy(out.data(), "PMTiles", 7);
  out[7] = 3;
  const uint64_t v[] = {h.rootOffset,     h.rootLength,  h.metadataOffset, h.metadataLength,
                        h.leafOffset,     h.leafLength,  h.tileDataOffset, h.tileDataLength,
                        h.addressedTiles, h.tileEntries, h.tileContents};
  for (size_t i = 0; i < std::size(v); ++i) put64(out, 8 + 8 * i, v[i]);
  out[96] = h.clustered ? 1 : 0;
  out[97] = static_cast<uint8_t>(h.internalCompression);
  out[98] = static_cast<uint8_t>(h.tileCompression);
  out[99] = static_cast<uint8_t>(h.tileType);
  out[100] = static_cast<uint8_t>(h.minZoom), out[101] = static_cast<uint8_t>(h.maxZoom);
  put32(out, 102, h.minLonE7), put32(out, 106, h.minLatE7), put32(out, 110, h.maxLonE7), put32(out, 114, h.maxLatE7);
  out[118] = static_cast<uint8_t>(h.centerZoom);
  put32(out, 119, h.centerLonE7), put32(out, 123, h.centerLatE7);
  return out;
}

Result<std::vector<uint8_t>> gunzip(std::span<const uint8_t> bytes, const std::string& name, size_t maxBytes) {
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) return makeError(ErrorKind::Internal, "zlib: inflateInit2 failed");
  std::vector<uint8_t> out;
  zs.next_in = const_cast<Bytef*>(bytes.data());
  zs.avail_in = static_cast<uInt>(std::min<size_t>(bytes.size(), 0xffffffffu));
  int rc = Z_OK;
  while (rc == Z_OK) {
    if (out.size() >= maxBytes) break;
    const size_t grow = std::min<size_t>(std::max<size_t>(out.size(), 4096), maxBytes - out.size());
    out.resize(out.size() + grow);
    zs.next_out = out.data() + (out.size() - grow);
    zs.avail_out = static_cast<uInt>(grow);
    rc = inflate(&zs, Z_NO_FLUSH);
    out.resize(out.size() - zs.avail_out);
    if (rc == Z_BUF_ERROR && zs.avail_in == 0) break;  // input ended before the stream did
    if (rc == Z_BUF_ERROR) rc = Z_OK;
  }
  const bool whole = rc == Z_STREAM_END && zs.avail_in == 0;
  inflateEnd(&zs);
  if (!whole)
    return makeError(ErrorKind::InvalidInput,
                     concat("'", name, "': ",
                            out.size() >= maxBytes ? concat("gzip data inflates beyond ", maxBytes, " bytes")
                                                   : std::string("corrupt or truncated gzip data")));
  return out;
}

Result<std::vector<PmtilesEntry>> decodePmtilesDirectory(std::span<const uint8_t> bytes, PmtilesCompression compression,
                                                         const std::string& name, size_t maxEntries) {
  std::vector<uint8_t> inflated;
  if (compression == PmtilesCompression::Gzip) {
    auto g = gunzip(bytes, name, std::max<size_t>(maxEntries, 1) * 40);  // ≤ 4 varints of ≤ 10 bytes each
    if (!g) return bad(name, concat("directory: ", g.error().message));
    inflated = std::move(*g);
    bytes = inflated;
  } else if (compression != PmtilesCompression::None) {
    return makeError(ErrorKind::Unsupported,
                     concat("'", name, "': directories compressed with method ", static_cast<int>(compression),
                            "; vegstream reads uncompressed and gzip (1, 2)"));
  }
  size_t at = 0;
  uint64_t count = 0;
  if (!readVarint(bytes, at, count)) return bad(name, "directory: truncated entry count");
  // Every entry takes at least 4 bytes (one varint per column), so the count is bounded first.
  if (count == 0 || count > maxEntries || count > (bytes.size() - at) / 4)
    return bad(name, concat("directory: ", count, " entries in ", bytes.size(), " bytes"));
  std::vector<PmtilesEntry> e(count);
  uint64_t v = 0, id = 0;
  for (size_t i = 0; i < count; ++i) {
    if (!readVarint(bytes, at, v)) return bad(name, "directory: truncated tile ids");
    if ((i > 0 && v == 0) || v > ~uint64_t{0} - id) return bad(name, "directory: tile ids do not increase");
    e[i].tileId = id += v;
  }
  for (size_t i = 0; i < count; ++i) {
    if (!readVarint(bytes, at, v) || v > 0xffffffffu) return bad(name, "directory: bad run length");
    e[i].runLength = static_cast<uint32_t>(v);
  }
  for (size_t i = 0; i < count; ++i) {
    if (!readVarint(bytes, at, v) || v == 0 || v > 0xffffffffu) return bad(name, "directory: bad length");
    e[i].length = static_cast<uint32_t>(v);
  }
  for (size_t i = 0; i < count; ++i) {
    if (!readVarint(bytes, at, v)) return bad(name, "directory: truncated offsets");
    if (v == 0 && i == 0) return bad(name, "directory: the first offset refers to a previous entry");
    e[i].offset = v == 0 ? e[i - 1].offset + e[i - 1].length : v - 1;
  }
  if (at != bytes.size()) return bad(name, concat("directory: ", bytes.size() - at, " bytes after the entries"));
  return e;
}

std::vector<uint8_t> encodePmtilesDirectory(const std::vector<PmtilesEntry>& entries) {
  std::vector<uint8_t> out;
  writeVarint(out, entries.size());
  uint64_t last = 0;
  for (const auto& e : entries) writeVarint(out, e.tileId - last), last = e.tileId;
  for (const auto& e : entries) writeVarint(out, e.runLength);
  for (const auto& e : entries) writeVarint(out, e.length);
  for (size_t i = 0; i < entries.size(); ++i) {
    const bool follows = i > 0 && entries[i].offset == entries[i - 1].offset + entries[i - 1].length;
    writeVarint(out, follows ? 0 : entries[i].offset + 1);
  }
  return out;
}

uint64_t pmtilesFirstId(int z) {
  assert(z >= 0 && z <= 31);
  return ((uint64_t{1} << (2 * z)) - 1) / 3;
}

uint64_t pmtilesTileId(const geo::TileId& id) {
  assert(geo::isValid(id));
  uint64_t x = static_cast<uint64_t>(id.x), y = static_cast<uint64_t>(id.y), d = 0;
  for (uint64_t s = (uint64_t{1} << id.z) >> 1; s > 0; s >>= 1) {
    const uint64_t rx = (x & s) != 0, ry = (y & s) != 0;
    d += s * s * ((3 * rx) ^ ry);
    rotate(s, x, y, rx, ry);
  }
  return pmtilesFirstId(id.z) + d;
}

geo::TileId pmtilesTileZxy(uint64_t tileId) {
  int z = 0;
  while (z < 31 && pmtilesFirstId(z + 1) <= tileId) ++z;
  assert(z <= geo::kMaxTileZoom);
  uint64_t t = tileId - pmtilesFirstId(z), x = 0, y = 0;
  for (uint64_t s = 1; s < (uint64_t{1} << z); s <<= 1) {
    const uint64_t rx = 1 & (t / 2), ry = 1 & (t ^ rx);
    rotate(s, x, y, rx, ry);
    x += s * rx;
    y += s * ry;
    t /= 4;
  }
  return {z, static_cast<int>(x), static_cast<int>(y)};
}

std::optional<PmtilesEntry> findPmtilesEntry(const std::vector<PmtilesEntry>& entries, uint64_t tileId) {
  auto it = std::upper_bound(entries.begin(), entries.end(), tileId,
                             [](uint64_t id, const PmtilesEntry& e) { return id < e.tileId; });
  if (it == entries.begin()) return std::nullopt;
  const PmtilesEntry& e = *std::prev(it);
  if (e.runLength == 0 || tileId - e.tileId < e.runLength) return e;
  return std::nullopt;
}

}  // namespace vegstream::datasets
