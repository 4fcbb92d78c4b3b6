#pragma once
// A 32-bit integer hash finaliser (the "lowbias32" constants, after Wellons' hash-prospector):
// cheap, well mixed, the same on every platform — for deterministic procedural data (synthetic
// terrain, detail textures). Not the plant seeding hash: that is Philox (vegetation/).

#include <cstdint>

namespace vegstream {

inline uint32_t mix32(uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352dU;
  h ^= h >> 15;
  h *= 0x846ca68bU;
  h ^= h >> 16;
  return h;
}

}  // namespace vegstream
