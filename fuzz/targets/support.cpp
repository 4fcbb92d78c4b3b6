// fuzz/targets.h: statedSide.

#include "fuzz/targets.h"

namespace vegstream::fuzz {

int statedSide(std::span<const uint8_t> b) {
  static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (b.size() >= 24 && std::equal(kPng, kPng + 8, b.begin())) {
    const uint32_t w = (uint32_t{b[16]} << 24) | (uint32_t{b[17]} << 16) | (uint32_t{b[18]} << 8) | uint32_t{b[19]};
    return w >= 1 && w <= 8192 ? static_cast<int>(w) : 0;
  }
  if (b.size() >= 4 && b[0] == 0xff && b[1] == 0xd8) {
    for (size_t i = 2; i + 9 < b.size(); ++i) {
      if (b[i] != 0xff) continue;
      const uint8_t m = b[i + 1];
      if (m == 0xc0 || m == 0xc1 || m == 0xc2) {
        const int w = (int{b[i + 7]} << 8) | int{b[i + 8]};
        return w >= 1 && w <= 8192 ? w : 0;
      }
    }
  }
  return 0;
}

}  // namespace vegstream::fuzz
