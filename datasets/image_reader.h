#pragma once
// One OpenImageIO reader on bytes in memory (tile_codec.cpp): the tile decoders' way to open an
// image without OIIO's fall-back to every other reader it has.

#include <memory>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace vegstream::datasets {

// Opens the proxy's bytes with OIIO's reader of `format` ("png", "jpeg", "webp") and no other.
// ImageInput::open("tile.jpg", …) does not stop there: when the reader the extension names
// refuses the bytes, OIIO tries every reader it has (LibRaw, TIFF, OpenEXR, DPX, …) on them, so a
// corrupt tile reached readers no tile format needs, at milliseconds each (found profiling the
// imagery_tile fuzz target). nullptr and `error` set when that reader refuses the bytes. The
// proxy must outlive the reader.
std::unique_ptr<OIIO::ImageInput> openWithReaderOf(const char* format, OIIO::Filesystem::IOProxy& proxy,
                                                   std::string& error);

}  // namespace vegstream::datasets
