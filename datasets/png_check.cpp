// The PNG check before libpng (png_check.h): chunks, header, and an inflate of the image data
// that counts rows and checks their filter bytes, then the PNG rebuilt from its needed chunks.

#include "datasets/png_check.h"

#include <array>
#include <algorithm>
#include <cstring>
#include <optional>

#include <zlib.h>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

constexpr uint32_t kMaxPngInt = 0x7fffffffu;  // PNG's "unsigned integer" limit (2³¹ − 1)

uint32_t be32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

Error corrupt(const std::string& name, const std::string& what) {
  return makeError(ErrorKind::InvalidInput, concat("tile '", name, "' is corrupt (", what, ")"));
}

struct Header {
  uint32_t width = 0, height = 0;
  int bitDepth = 0, colourType = 0, interlace = 0;
  int channels() const {
    switch (colourType) {
      case 0: return 1;
      case 2: return 3;
      case 3: return 1;
      case 4: return 2;
      default: return 4;
    }
  }
  // Bytes of one row of `w` pixels, without the filter byte.
  uint64_t rowBytes(uint64_t w) const { return (w * static_cast<uint64_t>(channels() * bitDepth) + 7) / 8; }
};

std::optional<std::string> headerProblem(const Header& h) {
  if (h.width == 0 || h.height == 0 || h.width > kMaxPngInt || h.height > kMaxPngInt)
    return concat("IHDR size ", h.width, "x", h.height, " is impossible");
  const int d = h.bitDepth;
  bool depthOk = false;
  switch (h.colourType) {
    case 0: depthOk = d == 1 || d == 2 || d == 4 || d == 8 || d == 16; break;
    case 3: depthOk = d == 1 || d == 2 || d == 4 || d == 8; break;
    case 2:
    case 4:
    case 6: depthOk = d == 8 || d == 16; break;
    default: return concat("IHDR colour type ", h.colourType, " does not exist");
  }
  if (!depthOk) return concat("IHDR bit depth ", d, " is impossible with colour type ", h.colourType);
  if (h.interlace > 1) return concat("IHDR interlace method ", h.interlace, " does not exist");
  return std::nullopt;
}

// Bytes the image data inflates to: one filter byte and rowBytes per row of every (Adam7) pass.
struct Pass {
  uint64_t width, rows;
};
std::vector<Pass> passes(const Header& h) {
  if (h.interlace == 0) return {{h.width, h.height}};
  static constexpr uint64_t kX0[7] = {0, 4, 0, 2, 0, 1, 0}, kDx[7] = {8, 8, 4, 4, 2, 2, 1};
  static constexpr uint64_t kY0[7] = {0, 0, 4, 0, 2, 0, 1}, kDy[7] = {8, 8, 8, 4, 4, 2, 2};
  // Pixels start, start + step, … below `size`.
  const auto count = [](uint64_t size, uint64_t start, uint64_t step) {
    return size > start ? (size - start + step - 1) / step : 0;
  };
  std::vector<Pass> out;
  for (int p = 0; p < 7; ++p) {
    const uint64_t w = count(h.width, kX0[p], kDx[p]), r = count(h.height, kY0[p], kDy[p]);
    if (w > 0 && r > 0) out.push_back({w, r});
  }
  return out;
}

// Inflates the concatenated IDAT data without keeping it: the stream must end exactly at the
// end of the data, after exactly the rows the header implies, each starting with filter 0 … 4.
std::optional<std::string> imageDataProblem(const Header& h, const std::vector<std::span<const uint8_t>>& idat) {
  const std::vector<Pass> ps = passes(h);
  size_t pass = 0;
  uint64_t row = 0, posInRow = 0;  // position in the current row, 0 = its filter byte
  z_stream z{};
  if (inflateInit(&z) != Z_OK) return std::string("zlib cannot start");
  std::array<uint8_t, 16384> out{};
  int status = Z_OK;
  std::optional<std::string> problem;
  for (size_t c = 0; c < idat.size() && !problem && status != Z_STREAM_END; ++c) {
    z.next_in = const_cast<Bytef*>(idat[c].data());
    z.avail_in = static_cast<uInt>(idat[c].size());
    while (z.avail_in > 0 && !problem) {
      z.next_out = out.data();
      z.avail_out = static_cast<uInt>(out.size());
      status = inflate(&z, Z_NO_FLUSH);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
        problem = concat("the image data does not inflate: ", z.msg ? z.msg : "zlib error");
        break;
      }
      const size_t produced = out.size() - z.avail_out;
      for (size_t i = 0; i < produced && !problem;) {
        if (pass >= ps.size()) {
          problem = std::string("more image data than the header says");
          break;
        }
        const uint64_t rowLen = 1 + h.rowBytes(ps[pass].width);
        if (posInRow == 0 && out[i] > 4) problem = concat("row filter type ", int(out[i]), " does not exist");
        const uint64_t take = std::min<uint64_t>(rowLen - posInRow, produced - i);
        i += static_cast<size_t>(take);
        posInRow += take;
        if (posInRow == rowLen) {
          posInRow = 0;
          if (++row == ps[pass].rows) {
            row = 0;
            ++pass;
          }
        }
      }
      if (status == Z_STREAM_END) {
        if (z.avail_in > 0 || c + 1 < idat.size()) {
          // Empty IDAT chunks after the end are harmless; data is not.
          bool trailing = z.avail_in > 0;
          for (size_t k = c + 1; k < idat.size(); ++k) trailing = trailing || !idat[k].empty();
          if (trailing) problem = std::string("data after the end of the compressed image");
        }
        break;
      }
      if (status == Z_BUF_ERROR && z.avail_in > 0 && z.avail_out > 0) {
        problem = std::string("the image data does not inflate");
        break;
      }
    }
  }
  inflateEnd(&z);
  if (problem) return problem;
  if (status != Z_STREAM_END) return std::string("the compressed image data ends early");
  if (pass < ps.size()) return std::string("less image data than the header says");
  return std::nullopt;
}

bool isLetter(uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// What the chunks so far said.
struct ChunkWalk {
  std::optional<Header> header;
  bool havePalette = false, haveTrns = false, idatDone = false;
  uint32_t paletteEntries = 0;
  std::vector<std::span<const uint8_t>> idat;
};

// One chunk of type t (its type bytes at `type`, its data `data`) checked against what came before.
Status checkChunk(ChunkWalk& w, const std::string& t, const uint8_t* type, std::span<const uint8_t> data,
                  const std::string& name, uint32_t maxSide) {
  const auto len = static_cast<uint32_t>(data.size());
  if (t == "IHDR") {
    if (w.header) return corrupt(name, "a second IHDR chunk");
    if (len != 13) return corrupt(name, "IHDR is not 13 bytes");
    Header h;
    h.width = be32(&data[0]);
    h.height = be32(&data[4]);
    h.bitDepth = data[8];
    h.colourType = data[9];
    h.interlace = data[12];
    if (data[10] != 0 || data[11] != 0) return corrupt(name, "IHDR compression or filter method does not exist");
    if (auto p = headerProblem(h)) return corrupt(name, *p);
    if (h.width > maxSide || h.height > maxSide)  // before any inflate: the header bounds the work
      return makeError(ErrorKind::InvalidInput, concat("tile '", name, "' is ", h.width, "x", h.height,
                                                       " pixels; a tile here is at most ", maxSide, " pixels a side"));
    w.header = h;
  } else if (t == "PLTE") {
    if (w.havePalette || !w.idat.empty() || w.haveTrns) return corrupt(name, "PLTE is out of place");
    if (w.header->colourType == 0 || w.header->colourType == 4) return corrupt(name, "PLTE in a greyscale image");
    if (len == 0 || len % 3 != 0 || len / 3 > 256) return corrupt(name, "PLTE length is not 3 × 1 … 256");
    if (w.header->colourType == 3 && len / 3 > (1u << w.header->bitDepth))
      return corrupt(name, "PLTE has more entries than the bit depth can index");
    w.havePalette = true;
    w.paletteEntries = len / 3;
  } else if (t == "tRNS") {
    if (w.haveTrns || !w.idat.empty()) return corrupt(name, "tRNS is out of place");
    const int ct = w.header->colourType;
    const bool ok = (ct == 0 && len == 2) || (ct == 2 && len == 6) ||
                    (ct == 3 && w.havePalette && len >= 1 && len <= w.paletteEntries);
    if (!ok) return corrupt(name, "tRNS does not fit the colour type");
    w.haveTrns = true;
  } else if (t == "IDAT") {
    if (w.idatDone) return corrupt(name, "IDAT chunks are not consecutive");
    if (w.header->colourType == 3 && !w.havePalette) return corrupt(name, "a paletted image without PLTE");
    w.idat.push_back(data);
  } else if (t == "IEND") {
    if (len != 0) return corrupt(name, "IEND is not empty");
  } else if (!(type[0] & 0x20)) {
    return corrupt(name, concat("unknown critical chunk ", t));
  }
  return {};
}

}  // namespace

Result<std::vector<uint8_t>> checkedPng(std::span<const uint8_t> bytes, const std::string& name, uint32_t maxSide) {
  // Not every caller sniffs first (decodeCanopyTile does not): a body shorter than the signature
  // was read past its end (found by fuzz/, http_response).
  static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
    return corrupt(name, "no PNG signature: not a PNG");
  std::vector<uint8_t> kept(bytes.begin(), bytes.begin() + 8);  // the signature
  kept.reserve(bytes.size());
  ChunkWalk w;
  size_t at = 8;
  for (;;) {
    if (at + 12 > bytes.size()) return corrupt(name, "the PNG ends before its IEND chunk: truncated");
    const uint32_t len = be32(&bytes[at]);
    if (len > kMaxPngInt || len > bytes.size() - at - 12)
      return corrupt(name, "a PNG chunk runs past the end of the file: truncated");
    const uint8_t* type = &bytes[at + 4];
    const std::span<const uint8_t> data(&bytes[at + 8], len);
    if (static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), type, len + 4)) != be32(&bytes[at + 8 + len]))
      return corrupt(name, "a PNG chunk fails its CRC check");
    const std::string t(type, type + 4);
    if (!isLetter(type[0]) || !isLetter(type[1]) || !isLetter(type[2]) || !isLetter(type[3]))
      return corrupt(name, "a PNG chunk type is not four letters");
    const bool keep = t == "IHDR" || t == "PLTE" || t == "tRNS" || t == "IDAT" || t == "IEND";
    if (!w.header && t != "IHDR") return corrupt(name, "the PNG does not start with IHDR");
    if (Status c = checkChunk(w, t, type, data, name, maxSide); !c) return c.error();
    if (!w.idat.empty() && t != "IDAT") w.idatDone = true;
    if (keep) kept.insert(kept.end(), &bytes[at], &bytes[at + 12 + len]);
    at += 12 + len;
    if (t == "IEND") break;
  }
  if (w.idat.empty()) return corrupt(name, "the PNG has no image data (IDAT)");
  if (auto p = imageDataProblem(*w.header, w.idat)) return corrupt(name, *p);
  return kept;
}

}  // namespace vegstream::datasets
