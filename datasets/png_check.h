#pragma once
// A PNG checked in full before libpng (through OpenImageIO) decodes it. libpng reports a broken
// file by printing "libpng error: …" (and, for damaged ancillary chunks, "libpng warning: …") on
// stderr itself, before OIIO returns its own failure — which would break the command line's
// contract of one message per mistake (DESIGN.md). So everything libpng would complain about is
// found here first and becomes an error value naming the tile:
//   - the chunk structure: lengths inside the file and < 2³¹, every CRC, letters for types, IHDR
//     first and once, PLTE where the colour type needs or allows it, IDAT chunks consecutive,
//     IEND last, no unknown critical chunk;
//   - IHDR: size 1 … 2³¹ − 1, a valid bit depth for the colour type, compression / filter 0,
//     interlace 0 or 1; tRNS as long as the colour type says;
//   - the image data: the IDAT zlib stream inflates, checksum and all, to exactly the bytes the
//     header implies (Adam7 passes included), nothing after it, every row's filter type 0 … 4.
// What is returned is the PNG with only the chunks the decoder needs (IHDR, PLTE, tRNS, IDAT,
// IEND): the ancillary ones (text, gamma, colour profiles, …) are dropped, so none of them can
// make libpng warn (tiles carry heights and colours as bytes: no colour management applies).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::datasets {

// `bytes` starts with the PNG signature (the caller sniffed it). Errors are InvalidInput and
// name `name` ("tile 'NAME' is corrupt (…)"). A header wider or taller than `maxSide` pixels is
// refused as soon as IHDR is read, before a byte is inflated ("tile 'NAME' is WxH pixels; …").
Result<std::vector<uint8_t>> checkedPng(std::span<const uint8_t> bytes, const std::string& name, uint32_t maxSide);

}  // namespace vegstream::datasets
