#pragma once
// A tiny uncompressed little-endian TIFF writer for tests: OpenImageIO cannot write GeoTIFF
// tags, so the georeference cases (PixelIsPoint, model transformation, missing keys, bogus
// sizes) are built byte by byte here.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace vegstream::datasets::test {

struct TinyTag {
  uint16_t tag = 0;
  uint16_t type = 0;  // 2 ASCII, 3 SHORT, 4 LONG, 12 DOUBLE
  uint32_t count = 0;
  std::vector<uint8_t> bytes;
};

template <typename T>
TinyTag tinyTag(uint16_t tag, uint16_t type, const std::vector<T>& values) {
  TinyTag t{tag, type, static_cast<uint32_t>(values.size()), {}};
  t.bytes.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(t.bytes.data(), values.data(), t.bytes.size());
  return t;
}
inline TinyTag shorts(uint16_t tag, const std::vector<uint16_t>& v) { return tinyTag(tag, 3, v); }
inline TinyTag longs(uint16_t tag, const std::vector<uint32_t>& v) { return tinyTag(tag, 4, v); }
inline TinyTag doubles(uint16_t tag, const std::vector<double>& v) { return tinyTag(tag, 12, v); }
inline TinyTag ascii(uint16_t tag, const std::string& s) {
  std::vector<char> v(s.begin(), s.end());
  v.push_back('\0');
  return tinyTag(tag, 2, v);
}

struct TinyImage {
  uint32_t width = 2, height = 2;
  uint16_t channels = 1;
  uint16_t bits = 16;
  uint16_t sampleFormat = 1;    // 1 unsigned, 2 signed, 3 IEEE float
  std::vector<uint8_t> pixels;  // row-major, little-endian samples
  std::vector<TinyTag> extra;   // GeoTIFF tags and the like
  // Replaces ImageWidth/ImageLength in the header only (pixels stay small): a bogus size.
  uint32_t claimedWidth = 0, claimedHeight = 0;
};

inline void writeTinyTiff(const std::filesystem::path& path, const TinyImage& img) {
  std::vector<TinyTag> tags = {
      longs(256, {img.claimedWidth ? img.claimedWidth : img.width}),
      longs(257, {img.claimedHeight ? img.claimedHeight : img.height}),
      shorts(258, std::vector<uint16_t>(img.channels, img.bits)),
      shorts(259, {1}),
      shorts(262, {static_cast<uint16_t>(img.channels >= 3 ? 2 : 1)}),
      longs(273, {0}),  // strip offset, patched below
      shorts(277, {img.channels}),
      longs(278, {img.height}),
      longs(279, {static_cast<uint32_t>(img.pixels.size())}),
      shorts(284, {1}),
      shorts(339, std::vector<uint16_t>(img.channels, img.sampleFormat)),
  };
  tags.insert(tags.end(), img.extra.begin(), img.extra.end());
  std::sort(tags.begin(), tags.end(), [](const auto& a, const auto& b) { return a.tag < b.tag; });

  // Layout: header, IFD, out-of-line values, pixels.
  const uint32_t ifdSize = static_cast<uint32_t>(2 + 12 * tags.size() + 4);
  uint32_t next = 8 + ifdSize;
  std::vector<uint32_t> offsets;
  for (const auto& t : tags) {
    offsets.push_back(next);
    if (t.bytes.size() > 4) next += static_cast<uint32_t>((t.bytes.size() + 1) & ~size_t{1});
  }
  const uint32_t pixelOffset = next;
  for (auto& t : tags)
    if (t.tag == 273) std::memcpy(t.bytes.data(), &pixelOffset, 4);

  std::vector<uint8_t> out = {'I', 'I', 42, 0, 8, 0, 0, 0};
  auto put = [&out](const void* p, size_t n) {
    out.insert(out.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
  };
  const auto n = static_cast<uint16_t>(tags.size());
  put(&n, 2);
  for (size_t i = 0; i < tags.size(); ++i) {
    const auto& t = tags[i];
    put(&t.tag, 2);
    put(&t.type, 2);
    put(&t.count, 4);
    uint8_t field[4] = {0, 0, 0, 0};
    if (t.bytes.size() <= 4)
      std::memcpy(field, t.bytes.data(), t.bytes.size());
    else
      std::memcpy(field, &offsets[i], 4);
    put(field, 4);
  }
  const uint32_t zero = 0;
  put(&zero, 4);
  for (const auto& t : tags) {
    if (t.bytes.size() <= 4) continue;
    put(t.bytes.data(), t.bytes.size());
    if (t.bytes.size() % 2) out.push_back(0);
  }
  put(img.pixels.data(), img.pixels.size());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
}

template <typename T>
std::vector<uint8_t> pixelBytes(const std::vector<T>& v) {
  std::vector<uint8_t> b(v.size() * sizeof(T));
  std::memcpy(b.data(), v.data(), b.size());
  return b;
}

}  // namespace vegstream::datasets::test
