#pragma once
// Nested wedgie thicknesses of one height tile's bintree (ROAM, Duchaineau et al. 1997 §5;
// seed 001_3eca9f2c7752e4fb.txt §3.1): for every triangle of the tile's own bintree (the two
// halves of the tile's square, split down to half-pixel squares, with the diagonals the
// dataset's bintree gives them: bintree.h), the thickness e_T such that the height surface
// under T lies within T's plane ± e_T:
//     e_T = |h(m) − (h(left) + h(right)) / 2| + max(e_child0, e_child1),   e = 0 below the pixels,
// where h is the tile's bilinear surface at pixel corners (the average of the four pixels
// around a corner, clamped at the tile's edge) and m the base midpoint. Nested by construction:
// a child's thickness never exceeds its parent's, so the wedgie of a triangle contains the
// wedgies of all its descendants (what hierarchical culling needs).
//
// Nodata: a triangle with a nodata corner or midpoint but data somewhere under it is "partial":
// its thickness is at least half its hypotenuse (it must be refined until the edge of the data
// is resolved); a triangle without any data under it has no thickness (kNoData).
//
// Stored down to kStoredLevels (a half of a 4 × 4-pixel square, 64 KiB a tile); the levels
// below, down to the pixels, are computed when asked (deepThickness: at most 31 triangles).
// Built on a decode thread, read by the frame thread.

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "datasets/tile_codec.h"
#include "streaming/tile_streamer.h"
#include "terrain/bintree.h"

namespace vegstream::terrain {

inline constexpr int kStoredLevels = 12;
inline constexpr float kNoData = -1.0f;

class WedgieTable final : public streaming::TileExtra {
 public:
  // `rootZoom`: the dataset bintree's root zoom (decides the diagonals, bintree.h).
  WedgieTable(const datasets::HeightTile& tile, int rootZoom);

  const geo::TileId& tile() const { return tile_; }
  // Thickness (m) of the tile-bintree triangle of `level` (0 = a half of the tile's square)
  // whose centroid is at `centroidPx` (pixel units of this tile, [0, 256]²); kNoData if there is
  // no data under it.
  float thickness(int level, glm::dvec2 centroidPx) const;
  // The same for a triangle deeper than kStoredLevels (≤ kTileLevels), from the tile's heights
  // (`tile` is the one this table was made from); corners in pixel-corner coordinates of the tile.
  float deepThickness(const datasets::HeightTile& tile, const TriCorners& cornersPx, int level) const;
  uint64_t bytes() const override { return errors_.size() * sizeof(float) + sizeof(*this); }
  // Where the thickness of that triangle is stored (level ≤ kStoredLevels).
  size_t thicknessIndex(int level, glm::dvec2 centroidPx) const;

 private:
  geo::TileId tile_;
  int rootZoom_ = 0;
  double pixelM_ = 0.0;  // a pixel's ground size at the tile's centre (pixelGroundM, asked for every deep triangle)
  std::vector<float> errors_;  // level by level, then square row-major, then part
};

// The decode-thread hook for streaming::StreamingOptions::heightExtra.
streaming::HeightExtraFn wedgieTableBuilder(int rootZoom);
// What one table adds to a tile's bytes (StreamingOptions::heightExtraBytes).
uint64_t wedgieTableBytes();

}  // namespace vegstream::terrain
