// Seeded byte mutations of image files (binary_mutations.h), splitmix64-driven so that a
// failing (seed, index) replays exactly.

#include "tests/fuzz/binary_mutations.h"

#include <array>
#include <cstddef>

#include "tests/fuzz/mutation_rng.h"

namespace vegstream::testing {
namespace {

using Rng = MutationRng;

Rng rngFor(uint64_t seed, uint64_t index) { return mutationRng(seed, index); }

// Values that break decoders: zero, all ones, sign bits, sizes just past limits.
constexpr std::array<uint8_t, 8> kInteresting = {0x00, 0xff, 0x7f, 0x80, 0x01, 0x10, 0x40, 0xfe};

// One byte-level edit of `b`.
void edit(std::vector<uint8_t>& b, Rng& rng, std::string& what) {
  const size_t n = b.size();
  switch (rng.below(6)) {
    case 0: {  // flip one byte
      if (n == 0) return;
      const size_t p = rng.below(n);
      b[p] = static_cast<uint8_t>(b[p] ^ (1 + rng.below(255)));
      what += "flip " + std::to_string(p) + "; ";
      return;
    }
    case 1: {  // an interesting value
      if (n == 0) return;
      const size_t p = rng.below(n);
      b[p] = kInteresting[rng.below(kInteresting.size())];
      what += "set " + std::to_string(p) + "; ";
      return;
    }
    case 2: {  // cut short
      const size_t len = rng.below(n);
      b.resize(len);
      what += "truncate to " + std::to_string(len) + "; ";
      return;
    }
    case 3: {  // random bytes inserted
      const size_t p = rng.below(n + 1), len = 1 + rng.below(16);
      std::vector<uint8_t> junk(len);
      for (uint8_t& j : junk) j = rng.byte();
      b.insert(b.begin() + static_cast<std::ptrdiff_t>(p), junk.begin(), junk.end());
      what += "insert " + std::to_string(len) + " at " + std::to_string(p) + "; ";
      return;
    }
    case 4: {  // a range erased
      if (n == 0) return;
      const size_t p = rng.below(n), len = std::min(n - p, 1 + rng.below(64));
      b.erase(b.begin() + static_cast<std::ptrdiff_t>(p), b.begin() + static_cast<std::ptrdiff_t>(p + len));
      what += "erase " + std::to_string(len) + " at " + std::to_string(p) + "; ";
      return;
    }
    default: {  // a range repeated
      if (n == 0) return;
      const size_t p = rng.below(n), len = std::min(n - p, 1 + rng.below(64));
      const std::vector<uint8_t> copy(b.begin() + static_cast<std::ptrdiff_t>(p),
                                      b.begin() + static_cast<std::ptrdiff_t>(p + len));
      b.insert(b.begin() + static_cast<std::ptrdiff_t>(p), copy.begin(), copy.end());
      what += "repeat " + std::to_string(len) + " at " + std::to_string(p) + "; ";
      return;
    }
  }
}

uint32_t crc32(const uint8_t* data, size_t n) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

struct Chunk {
  std::array<uint8_t, 4> type;
  std::vector<uint8_t> data;
};

// The chunks of a valid PNG (after its 8-byte signature).
std::vector<Chunk> chunksOf(const std::vector<uint8_t>& png) {
  std::vector<Chunk> chunks;
  size_t at = 8;
  while (at + 12 <= png.size()) {
    const uint32_t len = (uint32_t{png[at]} << 24) | (uint32_t{png[at + 1]} << 16) | (uint32_t{png[at + 2]} << 8) |
                         uint32_t{png[at + 3]};
    if (len > png.size() - at - 12) break;
    Chunk c;
    for (size_t k = 0; k < 4; ++k) c.type[k] = png[at + 4 + k];
    c.data.assign(png.begin() + static_cast<std::ptrdiff_t>(at + 8),
                  png.begin() + static_cast<std::ptrdiff_t>(at + 8 + len));
    chunks.push_back(std::move(c));
    at += 12 + len;
  }
  return chunks;
}

std::vector<uint8_t> assemble(const std::vector<uint8_t>& signature, const std::vector<Chunk>& chunks) {
  std::vector<uint8_t> out(signature.begin(), signature.begin() + 8);
  for (const Chunk& c : chunks) {
    put32(out, static_cast<uint32_t>(c.data.size()));
    std::vector<uint8_t> typed(c.type.begin(), c.type.end());
    typed.insert(typed.end(), c.data.begin(), c.data.end());
    out.insert(out.end(), typed.begin(), typed.end());
    put32(out, crc32(typed.data(), typed.size()));
  }
  return out;
}

}  // namespace

ByteMutation mutateBytes(const std::vector<uint8_t>& valid, uint64_t seed, uint64_t index) {
  Rng rng = rngFor(seed, index);
  ByteMutation m{valid, ""};
  for (size_t e = 0, edits = 1 + rng.below(3); e < edits; ++e) edit(m.bytes, rng, m.what);
  return m;
}

ByteMutation mutatePng(const std::vector<uint8_t>& validPng, uint64_t seed, uint64_t index) {
  if (index % 2 == 0) return mutateBytes(validPng, seed, index);
  Rng rng = rngFor(seed ^ 0x504e47ULL, index);
  std::vector<Chunk> chunks = chunksOf(validPng);
  if (chunks.empty()) return mutateBytes(validPng, seed, index);
  ByteMutation m{{}, ""};
  const size_t pick = rng.below(3);
  if (pick == 0 && chunks.size() > 1 && rng.below(4) == 0) {  // a whole chunk dropped or repeated
    const size_t c = rng.below(chunks.size());
    if (rng.below(2) == 0) {
      m.what = "drop chunk " + std::to_string(c) + "; ";
      chunks.erase(chunks.begin() + static_cast<std::ptrdiff_t>(c));
    } else {
      m.what = "repeat chunk " + std::to_string(c) + "; ";
      chunks.insert(chunks.begin() + static_cast<std::ptrdiff_t>(c), chunks[c]);
    }
  } else {
    // IHDR (the first chunk: size, bit depth, colour type, …) a third of the time, else any chunk.
    const size_t c = pick == 1 ? 0 : rng.below(chunks.size());
    std::string kind(chunks[c].type.begin(), chunks[c].type.end());
    m.what = "inside " + kind + " (CRC repaired): ";
    for (size_t e = 0, edits = 1 + rng.below(2); e < edits; ++e) edit(chunks[c].data, rng, m.what);
  }
  m.bytes = assemble(validPng, chunks);
  return m;
}

}  // namespace vegstream::testing
