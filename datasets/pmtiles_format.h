#pragma once
// PMTiles version 3, the parts a reader needs, as pure functions on bytes (no I/O), so that
// every decoder of untrusted input here is fuzzed on its own (tests/fuzz/).
// Spec: https://github.com/protomaps/PMTiles/blob/main/spec/v3/spec.md
//
// - Header: 127 bytes, little-endian: magic "PMTiles", version 3, offsets and lengths of the
//   root directory, JSON metadata, leaf directories and tile data, counts, clustered flag,
//   internal / tile compression, tile type, min / max zoom, bounds and centre (lon/lat · 10⁷).
// - Tile ids: the tiles of all zooms below z come first (Σ 4^i, i < z = (4^z − 1) / 3), then the
//   position of (x, y) on the Hilbert curve of zoom z.
// - Directory: varint entry count (> 0); then the columns tile id (delta-coded), run length,
//   length, offset (0: previous offset + previous length; else offset + 1), each a varint; the
//   whole possibly compressed (InternalCompression; gzip supported here). Run length 0: the
//   entry points at a leaf directory (offset relative to the leaf-directory section); else at
//   tile data (relative to the tile-data section) for run-length consecutive tile ids.
//
// Every count read from the input is checked against the bytes that could hold it before
// anything is allocated; errors are InvalidInput naming `name` (the archive's path or URL).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

inline constexpr size_t kPmtilesHeaderBytes = 127;
// The spec puts the header and the root directory in the first 16 KiB: one read fetches both.
inline constexpr size_t kPmtilesFirstReadBytes = 16384;

enum class PmtilesCompression : uint8_t { Unknown = 0, None = 1, Gzip = 2, Brotli = 3, Zstd = 4 };
enum class PmtilesTileType : uint8_t { Unknown = 0, Mvt = 1, Png = 2, Jpeg = 3, Webp = 4, Avif = 5 };

struct PmtilesHeader {
  uint64_t rootOffset = 0, rootLength = 0;
  uint64_t metadataOffset = 0, metadataLength = 0;
  uint64_t leafOffset = 0, leafLength = 0;
  uint64_t tileDataOffset = 0, tileDataLength = 0;
  uint64_t addressedTiles = 0, tileEntries = 0, tileContents = 0;
  bool clustered = false;
  PmtilesCompression internalCompression = PmtilesCompression::None;
  PmtilesCompression tileCompression = PmtilesCompression::None;
  PmtilesTileType tileType = PmtilesTileType::Unknown;
  int minZoom = 0, maxZoom = 0;
  int32_t minLonE7 = 0, minLatE7 = 0, maxLonE7 = 0, maxLatE7 = 0;
  int centerZoom = 0;
  int32_t centerLonE7 = 0, centerLatE7 = 0;
};

struct PmtilesEntry {
  uint64_t tileId = 0;
  uint64_t offset = 0;  // relative to the tile-data section, or the leaf section (runLength 0)
  uint32_t length = 0;
  uint32_t runLength = 0;  // 0: a leaf directory
};

// Bad magic, another version, fewer than 127 bytes, zooms above 30 or min > max, sections
// beyond `fileSize` (when known), compressions / tile types outside the enums → InvalidInput.
Result<PmtilesHeader> decodePmtilesHeader(std::span<const uint8_t> bytes, const std::string& name,
                                          std::optional<uint64_t> fileSize = std::nullopt);
std::vector<uint8_t> encodePmtilesHeader(const PmtilesHeader& header);  // 127 bytes (tests, writers)

// A directory's bytes (compressed as `compression` says) → its entries, sorted by tile id.
// At most `maxEntries` entries; a tile id that does not increase, a length of 0, an offset of 0
// on the first entry, trailing bytes, or a truncated varint → InvalidInput.
Result<std::vector<PmtilesEntry>> decodePmtilesDirectory(std::span<const uint8_t> bytes,
                                                         PmtilesCompression compression, const std::string& name,
                                                         size_t maxEntries = 1u << 22);
// Uncompressed serialisation of entries (sorted by tile id, lengths > 0): tests and writers.
std::vector<uint8_t> encodePmtilesDirectory(const std::vector<PmtilesEntry>& entries);

// gzip (RFC 1952) → bytes, at most maxBytes of output; anything else → InvalidInput naming `name`.
Result<std::vector<uint8_t>> gunzip(std::span<const uint8_t> bytes, const std::string& name, size_t maxBytes);

uint64_t pmtilesTileId(const geo::TileId& id);  // valid id with z ≤ 30 (asserted)
geo::TileId pmtilesTileZxy(uint64_t tileId);    // tileId < pmtilesFirstId(31)
uint64_t pmtilesFirstId(int z);                 // (4^z − 1) / 3: the first tile id of zoom z

// The entry that covers `tileId`: the last entry with entry.tileId ≤ tileId, if it is a leaf
// (a leaf covers everything up to the next entry) or a run that reaches it
// (tileId < entry.tileId + runLength). nullopt: no entry covers it.
std::optional<PmtilesEntry> findPmtilesEntry(const std::vector<PmtilesEntry>& entries, uint64_t tileId);

}  // namespace vegstream::datasets
