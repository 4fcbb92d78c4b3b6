#pragma once
// Seeded, deterministic mutations of a valid image file (an elevation or imagery tile): bytes
// flipped, the file cut short, random bytes inserted, a range erased or repeated. A PNG's chunks
// carry CRCs, which the decoder checks first (datasets/tile_codec.cpp), so a plain flip rarely
// gets past them; `mutatePng` therefore also edits inside one chunk (IHDR fields, IDAT's zlib
// stream, …) and writes the chunk back with a correct length and CRC, so libpng itself sees
// the damage.

#include <cstdint>
#include <string>
#include <vector>

namespace vegstream::testing {

struct ByteMutation {
  std::vector<uint8_t> bytes;
  std::string what;  // for failure messages
};

// Mutation number `index` of `valid` under `seed` (any format): one to three byte-level edits.
ByteMutation mutateBytes(const std::vector<uint8_t>& valid, uint64_t seed, uint64_t index);

// For a valid PNG: every other index a chunk-aware edit with the CRC repaired, else mutateBytes.
ByteMutation mutatePng(const std::vector<uint8_t>& validPng, uint64_t seed, uint64_t index);

}  // namespace vegstream::testing
