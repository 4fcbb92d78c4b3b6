#pragma once
// Heights and normals of the ground over whatever height tiles are resident: bilinear in the
// finest resident tile at each point (its own max-zoom tile or the nearest resident ancestor),
// for the ROAM mesh, the flight, the colliders and the vegetation; and the wedgie thickness of a
// bintree triangle from the finest resident tile that contains it (wedgie_table.h).
//
// Tiles are found through an injected lookup (the streamer's findResident in a flight, a map of
// tiles in tests) and cached for the frame: call newFrame() after every streamer update, since
// a resident tile may have been evicted (a cached pointer is valid only until then).
//
// Pixel convention as everywhere: pixel (i, j) of a tile is centred at (i + 0.5, j + 0.5).
// Sampling is bilinear in the pixel grid of the finest resident tile's zoom, reading across its
// edge from the neighbouring tile of that zoom when it is resident (so heights are continuous
// across tile borders) and clamping otherwise; nodata (NaN) wherever a neighbour with non-zero
// weight is nodata.

#include <cstdint>
#include <functional>
#include <limits>
#include <unordered_map>

#include <glm/vec2.hpp>

#include "datasets/tile_codec.h"
#include "streaming/tile_streamer.h"
#include "terrain/bintree.h"

namespace vegstream::terrain {

class WedgieTable;

// Bilinear height of `tile` at fractional tile coordinates of zoom z (x + fx, y + fy for a point
// of tile (z, x, y)); the point should lie in the tile's area (clamped otherwise).
double sampleHeight(const datasets::HeightTile& tile, int z, double tileX, double tileY);

struct HeightSample {
  double heightM = std::numeric_limits<double>::quiet_NaN();  // metres above the ellipsoid datum of the tiles
  glm::dvec2 slope{0.0};  // dh/d(east), dh/d(north), metres per metre (central differences, one pixel)
  int sourceZoom = -1;    // zoom of the tile it came from; −1: nothing resident there
};

class ResidentHeights {
 public:
  // The tile at or above `tile` nearest to it that is resident, or null; valid until newFrame().
  using Find = std::function<const streaming::ResidentTile*(const geo::TileId& tile)>;

  ResidentHeights(BintreeGrid grid, Find find);

  void newFrame() { cache_.clear(); }
  const BintreeGrid& grid() const { return grid_; }

  HeightSample sample(GridPoint p);
  HeightSample sampleLonLat(double latDeg, double lonDeg);

  // Wedgie thickness (m) of a bintree triangle; kNoData when the finest resident tile over it
  // has no data there; NaN when no height tile over it is resident (or has no table).
  float thickness(const TriCorners& t, int level);

  // The finest resident height tile at or above `tile` (cached for the frame).
  const streaming::ResidentTile* find(const geo::TileId& tile);

 private:
  HeightSample sampleTileXY(glm::dvec2 xy, int z);
  // Its height alone (NaN where nothing is resident): the slope costs four more bilinear
  // samples, a projection and a cosine, which a thickness below the pixels does not need.
  double heightTileXY(glm::dvec2 xy, int z);
  double bilinearAcross(const datasets::HeightTile& tile, int z, glm::dvec2 xy);

  BintreeGrid grid_;
  Find find_;
  std::unordered_map<uint64_t, const streaming::ResidentTile*> cache_;
};

// The lookup of a flight: the streamer's nearest resident height tile (marks it used).
ResidentHeights::Find findResidentHeights(streaming::TileStreamer& streamer);

}  // namespace vegstream::terrain
