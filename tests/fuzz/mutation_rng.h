#pragma once
// The mutation tests' random stream: splitmix64 — tiny, seedable, and the same on every
// platform (unlike std:: distributions) — one stream per (seed, index), so a failing mutation
// replays exactly.

#include <cstddef>
#include <cstdint>

namespace vegstream::testing {

struct MutationRng {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(next() % n); }
  uint8_t byte() { return static_cast<uint8_t>(next() & 0xff); }
};

// The stream of mutation `index` of a test seeded with `seed`.
inline MutationRng mutationRng(uint64_t seed, uint64_t index) {
  MutationRng rng{seed * 0x100000001b3ULL ^ (index + 1) * 0x9e3779b97f4a7c15ULL};
  rng.next();
  return rng;
}

}  // namespace vegstream::testing
