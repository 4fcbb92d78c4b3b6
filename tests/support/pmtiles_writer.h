#pragma once
// A minimal PMTiles v3 writer for the tests, written from the spec
// (https://github.com/protomaps/PMTiles/blob/main/spec/v3/spec.md) independently of the reader
// in datasets/pmtiles_format.cpp — its own varints, Hilbert ids and header layout — so that a
// mistake in the reader is not mirrored here.
//
// Layout: header (127 bytes), root directory, JSON metadata "{}", leaf directories, tile data.
// Consecutive tile ids with identical bytes become one entry with a run length; identical bytes
// elsewhere share one offset. With maxRootEntries > 0 the entries are cut into leaves of that
// many entries and the root holds one leaf entry (run length 0) per leaf.

#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

#include "geo/xyz_tiles.h"

namespace vegstream::testing {

struct PmtilesWriteOptions {
  bool gzipDirectories = false;
  bool gzipTiles = false;
  size_t maxRootEntries = 0;  // 0: every entry in the root
  uint8_t tileType = 2;       // PNG
};

uint64_t referenceTileId(const geo::TileId& id);  // the spec's Hilbert id, computed here

std::vector<uint8_t> buildPmtiles(const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                                  const PmtilesWriteOptions& options = {});
void writePmtiles(const std::filesystem::path& path, const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                  const PmtilesWriteOptions& options = {});

// gzip (RFC 1952) of bytes, through zlib.
std::vector<uint8_t> gzipBytes(const std::vector<uint8_t>& bytes);

}  // namespace vegstream::testing
