// datasets/png_check.h on PNGs built byte by byte here (zlib for the image data): every kind a
// tile may legitimately be — RGBA, RGB, grey, grey + alpha, paletted with tRNS, 16-bit, Adam7
// interlaced at odd sizes, image data split over several IDATs, ancillary chunks — passes the
// check and decodes to the pixels it holds; each way of being broken that libpng would print
// about is refused with a message naming the tile.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "datasets/png_check.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {
namespace {

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void chunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data) {
  put32(png, static_cast<uint32_t>(data.size()));
  std::vector<uint8_t> typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  put32(png, static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), typed.data(), static_cast<uInt>(typed.size()))));
}

struct Image {
  uint32_t size = 0;
  int bitDepth = 8, colourType = 6, interlace = 0;
  std::vector<uint8_t> palette, trns;
  // Sample of channel c of pixel (x, y), 0 … 2^bitDepth − 1.
  uint32_t sample(uint32_t x, uint32_t y, int c) const {
    const uint32_t max = (1u << bitDepth) - 1u;
    // Opaque: OIIO hands partly transparent pixels over premultiplied by their alpha.
    if ((colourType == 4 || colourType == 6) && c == channels() - 1) return max;
    return (x * 37u + y * 11u + static_cast<uint32_t>(c) * 71u) % (max + 1u);
  }
  int channels() const {
    return colourType == 0 || colourType == 3 ? 1 : colourType == 4 ? 2 : colourType == 2 ? 3 : 4;
  }
};

// The filtered rows (filter 0) of the pixels (x0 + i·dx, y0 + j·dy).
void appendRows(const Image& im, uint32_t x0, uint32_t dx, uint32_t y0, uint32_t dy, std::vector<uint8_t>& raw) {
  for (uint32_t y = y0; y < im.size; y += dy) {
    if (x0 >= im.size) return;
    raw.push_back(0);
    uint32_t acc = 0, bits = 0;
    for (uint32_t x = x0; x < im.size; x += dx)
      for (int c = 0; c < im.channels(); ++c) {
        const uint32_t v = im.sample(x, y, c);
        if (im.bitDepth == 16) {
          raw.push_back(static_cast<uint8_t>(v >> 8));
          raw.push_back(static_cast<uint8_t>(v & 0xff));
          continue;
        }
        acc = (acc << im.bitDepth) | v;
        bits += static_cast<uint32_t>(im.bitDepth);
        if (bits == 8) {
          raw.push_back(static_cast<uint8_t>(acc));
          acc = bits = 0;
        }
      }
    if (bits > 0) raw.push_back(static_cast<uint8_t>(acc << (8 - bits)));
  }
}

std::vector<uint8_t> rawData(const Image& im) {
  std::vector<uint8_t> raw;
  if (im.interlace == 0) {
    appendRows(im, 0, 1, 0, 1, raw);
    return raw;
  }
  const uint32_t x0[7] = {0, 4, 0, 2, 0, 1, 0}, dx[7] = {8, 8, 4, 4, 2, 2, 1};
  const uint32_t y0[7] = {0, 0, 4, 0, 2, 0, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
  for (int p = 0; p < 7; ++p) appendRows(im, x0[p], dx[p], y0[p], dy[p], raw);
  return raw;
}

std::vector<uint8_t> deflate(const std::vector<uint8_t>& raw) {
  uLongf n = compressBound(static_cast<uLong>(raw.size()));
  std::vector<uint8_t> out(n);
  EXPECT_EQ(compress(out.data(), &n, raw.data(), static_cast<uLong>(raw.size())), Z_OK);
  out.resize(n);
  return out;
}

// A PNG of `im`; `edit` may change the chunks' data before they are written (the CRCs then
// match the edited data: only libpng's own checks can object).
struct Parts {
  std::vector<uint8_t> ihdr, idat, iend;
  bool splitIdat = false, ancillary = false;
};
Parts partsOf(const Image& im) {
  Parts p;
  put32(p.ihdr, im.size);
  put32(p.ihdr, im.size);
  p.ihdr.insert(p.ihdr.end(), {static_cast<uint8_t>(im.bitDepth), static_cast<uint8_t>(im.colourType), 0, 0,
                               static_cast<uint8_t>(im.interlace)});
  p.idat = deflate(rawData(im));
  return p;
}
std::vector<uint8_t> assemble(const Image& im, const Parts& p) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  chunk(png, "IHDR", p.ihdr);
  if (p.ancillary) chunk(png, "tEXt", {'S', 'o', 'f', 't', 0, 't', 'e', 's', 't'});
  if (!im.palette.empty()) chunk(png, "PLTE", im.palette);
  if (!im.trns.empty()) chunk(png, "tRNS", im.trns);
  if (p.splitIdat && p.idat.size() > 3) {
    const auto half = p.idat.begin() + static_cast<std::ptrdiff_t>(p.idat.size() / 2);
    chunk(png, "IDAT", {p.idat.begin(), half});
    chunk(png, "IDAT", {half, p.idat.end()});
  } else {
    chunk(png, "IDAT", p.idat);
  }
  if (p.ancillary) chunk(png, "zzZz", {1, 2, 3});  // unknown ancillary: allowed, dropped
  chunk(png, "IEND", p.iend);
  return png;
}

std::vector<Image> goodImages() {
  std::vector<Image> v;
  for (uint32_t size : {1u, 5u, 13u, 64u})
    for (int interlace : {0, 1}) {
      v.push_back({size, 8, 6, interlace, {}, {}});   // RGBA
      v.push_back({size, 8, 2, interlace, {}, {}});   // RGB
      v.push_back({size, 8, 0, interlace, {}, {}});   // grey
      v.push_back({size, 8, 4, interlace, {}, {}});   // grey + alpha
      v.push_back({size, 16, 6, interlace, {}, {}});  // 16-bit RGBA
      v.push_back({size, 1, 0, interlace, {}, {}});   // 1-bit grey
      Image pal{size, 4, 3, interlace, {}, {}};       // paletted, 16 entries, 3 transparent
      for (int i = 0; i < 16; ++i) pal.palette.insert(pal.palette.end(), {uint8_t(i * 16), uint8_t(255 - i), 7});
      pal.trns = {0, 128, 255};
      v.push_back(pal);
      v.push_back({size, 8, 0, interlace, {}, {0, 9}});  // grey with a transparent grey level
    }
  return v;
}

std::string describe(const Image& im) {
  return std::to_string(im.size) + "px depth " + std::to_string(im.bitDepth) + " type " +
         std::to_string(im.colourType) + (im.interlace ? " interlaced" : "");
}

TEST(PngCheck, EveryKindOfSoundPngPassesAndDecodes) {
  for (const Image& im : goodImages()) {
    for (int variant = 0; variant < 2; ++variant) {
      Parts p = partsOf(im);
      p.splitIdat = p.ancillary = variant == 1;
      const std::vector<uint8_t> png = assemble(im, p);
      const auto checked = checkedPng(png, "t.png", kMaxTileSide);
      ASSERT_TRUE(checked.ok()) << describe(im) << ": " << checked.error().message;
      EXPECT_LE(checked->size(), png.size());
      if (variant == 1) {
        EXPECT_LT(checked->size(), png.size()) << "the ancillary chunks are dropped";
      }
      const auto decoded = decodeColorTile(png, {}, static_cast<int>(im.size), "t.png");
      ASSERT_TRUE(decoded.ok()) << describe(im) << ": " << decoded.error().message;
      ASSERT_EQ(decoded->size, static_cast<int>(im.size));
      if (im.bitDepth == 8 && (im.colourType == 6 || im.colourType == 2)) {
        // The pixels themselves, interlaced or not.
        for (uint32_t y = 0; y < im.size; ++y)
          for (uint32_t x = 0; x < im.size; ++x)
            for (int c = 0; c < im.channels(); ++c)
              ASSERT_EQ(decoded->rgba[(y * im.size + x) * 4 + static_cast<uint32_t>(c)], im.sample(x, y, c))
                  << describe(im) << " at " << x << "," << y;
      }
    }
  }
}

TEST(PngCheck, WhatLibpngWouldPrintAboutIsRefusedNamingTheTile) {
  const Image im{13, 8, 6, 1, {}, {}};
  struct Case {
    const char* what;
    std::vector<uint8_t> png;
  };
  std::vector<Case> cases;
  const auto with = [&](const char* what, auto edit) {
    Parts p = partsOf(im);
    Image i = im;
    edit(p, i);
    cases.push_back({what, assemble(i, p)});
  };
  with("zero width", [](Parts& p, Image&) {
    p.ihdr[3] = 0;
    p.ihdr[2] = 0;
    p.ihdr[1] = 0;
    p.ihdr[0] = 0;
  });
  with("huge height", [](Parts& p, Image&) { p.ihdr[4] = 0x80; });
  with("bit depth 3", [](Parts& p, Image&) { p.ihdr[8] = 3; });
  with("colour type 5", [](Parts& p, Image&) { p.ihdr[9] = 5; });
  with("compression 1", [](Parts& p, Image&) { p.ihdr[10] = 1; });
  with("interlace 2", [](Parts& p, Image&) { p.ihdr[12] = 2; });
  with("IHDR of 12 bytes", [](Parts& p, Image&) { p.ihdr.pop_back(); });
  with("IEND with data", [](Parts& p, Image&) { p.iend = {1}; });
  with("image data cut short", [](Parts& p, Image&) { p.idat.resize(p.idat.size() / 2); });
  with("bad filter byte", [](Parts& p, Image& i) {
    std::vector<uint8_t> raw = rawData(i);
    raw[0] = 9;
    p.idat = deflate(raw);
  });
  with("too much image data", [](Parts& p, Image& i) {
    std::vector<uint8_t> raw = rawData(i);
    raw.insert(raw.end(), 100, 0);
    p.idat = deflate(raw);
  });
  with("too little image data", [](Parts& p, Image& i) {
    std::vector<uint8_t> raw = rawData(i);
    raw.resize(raw.size() - 5);
    p.idat = deflate(raw);
  });
  with("bytes after the zlib stream", [](Parts& p, Image&) { p.idat.insert(p.idat.end(), {1, 2, 3}); });
  with("broken zlib checksum", [](Parts& p, Image&) { p.idat.back() ^= 0x55; });
  with("tRNS with an alpha channel", [](Parts&, Image& i) { i.trns = {0, 0}; });
  with("PLTE in a grey image", [](Parts& p, Image& i) {
    p.ihdr[9] = 0;
    i.colourType = 0;
    p.idat = deflate(rawData(i));
    i.palette = {1, 2, 3};
  });
  with("paletted without PLTE", [](Parts& p, Image& i) {
    p.ihdr[9] = 3;
    i.colourType = 3;
    p.idat = deflate(rawData(i));
  });
  for (const Case& c : cases) {
    const auto r = checkedPng(c.png, "tiles/1/2/3.png", kMaxTileSide);
    ASSERT_FALSE(r.ok()) << c.what;
    EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput) << c.what;
    EXPECT_NE(r.error().message.find("tiles/1/2/3.png"), std::string::npos) << c.what << ": " << r.error().message;
  }
}

// A header that claims 100 000 × 100 000 pixels (40 GB of rows) is refused as soon as IHDR is
// read, before a byte is inflated: the check takes milliseconds, and a tile bigger than the
// dataset's size is refused at the same point.
TEST(PngCheck, TheSideLimitAppliesToTheHeaderBeforeAnyInflate) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> ihdr;
  put32(ihdr, 100000);
  put32(ihdr, 100000);
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});
  chunk(png, "IHDR", ihdr);
  // A zlib stream of zero rows that inflates without end: the old check inflated all of it.
  std::vector<uint8_t> zeros(size_t{1} << 20, 0);
  chunk(png, "IDAT", deflate(zeros));
  chunk(png, "IEND", {});
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = checkedPng(png, "imagery/14/1/2.png", kMaxTileSide);
  const auto decoded = decodeColorTile(png, {}, kTileSize, "imagery/14/1/2.png");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("is 100000x100000 pixels; a tile here is at most 4096"), std::string::npos)
      << r.error().message;
  ASSERT_FALSE(decoded.ok());
  EXPECT_NE(decoded.error().message.find("at most 256 pixels a side"), std::string::npos) << decoded.error().message;

  Image small;
  small.size = 300;
  const auto bigger = checkedPng(assemble(small, partsOf(small)), "t.png", 256);
  ASSERT_FALSE(bigger.ok());
  EXPECT_NE(bigger.error().message.find("is 300x300 pixels"), std::string::npos) << bigger.error().message;
}

}  // namespace
}  // namespace vegstream::datasets
