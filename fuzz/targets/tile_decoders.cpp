// The tile decoders (datasets/tile_codec.h) on any bytes: elevation (both encodings: the input's
// length parity picks one) and imagery (PNG, JPEG, WebP: sniffed from the bytes). The expected
// size is the one the image's header states, so every seed decodes in full and every mutation of
// it reaches the pixels; a decoded tile must be whole.

#include "datasets/tile_codec.h"
#include "fuzz/targets.h"

namespace vegstream::fuzz {

int elevationTile(const uint8_t* data, size_t size) {
  const auto bytes = asBytes(data, size);
  const int side = statedSide(bytes);
  const auto encoding = size % 2 ? datasets::ElevationEncoding::TerrainRgb : datasets::ElevationEncoding::Terrarium;
  const auto r = datasets::decodeHeightTile(bytes, {12, 758, 1608}, encoding, side, "fuzz/elevation/12/758/1608.png");
  checkResult(r);
  if (r) {
    VEGSTREAM_FUZZ_CHECK(r->size >= 1 && r->size <= datasets::kMaxTileSide);
    VEGSTREAM_FUZZ_CHECK(side == datasets::kAnyTileSize || r->size == side);
    VEGSTREAM_FUZZ_CHECK(r->heights.size() == static_cast<size_t>(r->size) * static_cast<size_t>(r->size));
  }
  return 0;
}

int imageryTile(const uint8_t* data, size_t size) {
  const auto bytes = asBytes(data, size);
  const int side = statedSide(bytes);
  const auto r = datasets::decodeColorTile(bytes, {12, 758, 1608}, side, "fuzz/imagery/12/758/1608");
  checkResult(r);
  if (r) {
    VEGSTREAM_FUZZ_CHECK(r->size >= 1 && r->size <= datasets::kMaxTileSide);
    VEGSTREAM_FUZZ_CHECK(side == datasets::kAnyTileSize || r->size == side);
    VEGSTREAM_FUZZ_CHECK(r->rgba.size() == static_cast<size_t>(r->size) * static_cast<size_t>(r->size) * 4);
  }
  return 0;
}

}  // namespace vegstream::fuzz
