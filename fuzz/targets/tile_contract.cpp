// The tile contract: a tile checked against the dataset.json it belongs to
// (streaming/tile_check.h tileCheckFor: decodes in the layer's encoding — the dataset's
// elevation encoding, PNG/JPEG imagery, one-channel 8-bit NDVI and landcover, 16-bit canopy — at
// the dataset's tile_size). Input layout: dataset.json's text, a NUL byte, one byte naming the
// layer (its low 3 bits), then the tile's bytes. A dataset.json that does not read ends the run
// (the dataset_json target covers it). A tile that passes must decode again, by the layer's own
// decoder, to exactly tile_size a side.

#include <cstring>
#include <string>

#include "datasets/canopy.h"
#include "datasets/dataset_format.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"
#include "fuzz/targets.h"
#include "streaming/tile_check.h"

namespace vegstream::fuzz {

int tileContract(const uint8_t* data, size_t size) {
  const void* nul = size == 0 ? nullptr : std::memchr(data, 0, size);
  if (nul == nullptr) return 0;
  const size_t jsonSize = static_cast<size_t>(static_cast<const uint8_t*>(nul) - data);
  if (jsonSize + 2 > size) return 0;
  const auto meta = datasets::parseDatasetMeta(asText(data, jsonSize), "fuzz/dataset.json");
  checkResult(meta);
  if (!meta) return 0;
  const uint8_t layer = data[jsonSize + 1] & 7;
  const auto tile = asBytes(data + jsonSize + 2, size - jsonSize - 2);
  const geo::TileId id{12, 758, 1608};
  const bool jpeg = meta->imagery == datasets::ImageryFormat::Jpeg;
  const char* path = layer == 0   ? "elevation/12/758/1608.png"
                     : layer == 1 ? (jpeg ? "imagery/12/758/1608.jpg" : "imagery/12/758/1608.png")
                     : layer == 2 ? "ndvi/12/758/1608.png"
                     : layer == 3 ? "landcover/12/758/1608.png"
                     : layer == 4 ? "canopy/12/758/1608.png"
                                  : "dataset.json";
  const streaming::TileCheck check = streaming::tileCheckFor(*meta, "fuzz");
  const Status s = check(path, tile);
  checkResult(s);
  if (!s || layer > 4) return 0;
  const int n = meta->tileSize;
  const size_t pixels = static_cast<size_t>(n) * static_cast<size_t>(n);
  switch (layer) {
    case 0: {
      const auto t = datasets::decodeHeightTile(tile, id, meta->elevationEncoding, n, path);
      VEGSTREAM_FUZZ_CHECK(t.ok() && t->size == n && t->heights.size() == pixels);
      break;
    }
    case 1: {
      const auto t = datasets::decodeColorTile(tile, id, n, path);
      VEGSTREAM_FUZZ_CHECK(t.ok() && t->size == n && t->rgba.size() == pixels * 4);
      break;
    }
    case 2: {
      const auto t = datasets::decodeNdviTile(tile, id, path, n);
      VEGSTREAM_FUZZ_CHECK(t.ok() && t->size() == pixels);
      break;
    }
    case 3: {
      const auto t = datasets::decodeLandcoverTile(tile, id, path, n);
      VEGSTREAM_FUZZ_CHECK(t.ok() && t->size == n && t->classes.size() == pixels);
      break;
    }
    case 4: {
      const auto t = datasets::decodeCanopyTile(tile, id, path, n);
      VEGSTREAM_FUZZ_CHECK(t.ok() && t->size == n && t->decimetres.size() == pixels);
      break;
    }
    default: break;
  }
  return 0;
}

}  // namespace vegstream::fuzz
