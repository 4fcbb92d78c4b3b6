#pragma once
// The mesh of one node chosen by tile_selection.h, built from the nearest resident height data:
// the node's own tile or an ancestor (coarser, but correct), so a node is never a hole while its
// tile streams in.
//
// Layout of NodeMesh::mesh.vertices:
//   [0, kGridVertices)            the grid: (kNodeQuads + 1)² vertices, row-major from the
//                                 north-west corner (row j, column i → j·(kNodeQuads+1) + i),
//                                 vertex (i, j) at tile position (x + i/kNodeQuads, y + j/kNodeQuads)
//   [kGridVertices, +4·kNodeQuads) the skirt: one vertex below each boundary vertex, in the
//                                 order of the boundary walked clockwise from above starting at
//                                 the north-west corner (north edge west → east, east edge north
//                                 → south, south edge east → west, west edge south → north).
// Heights: bilinear in the source tile's pixel space (pixel (i, j) centred at (i+0.5, j+0.5)),
// clamped at the tile's edge; nodata (NaN) where a neighbour with non-zero weight is nodata.
// Triangles touching a nodata vertex are left out (a hole, never a drop to zero); the skirt
// follows the grid's kept edges. Grid triangles are counter-clockwise seen from above, skirt
// triangles face away from the node.
//
// Skirts: each boundary vertex is repeated skirtDepthM lower (along the local up, through the
// geodetic → ENU map). Two same-level neighbours built from the same source share their edge
// vertices exactly; a level change or a different source leaves a gap at most the coarser
// surface's error, which the deeper of the two skirts hides.

#include <cstdint>
#include <optional>

#include "datasets/tile_codec.h"
#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"
#include "terrain/terrain_mesh.h"
#include "terrain/tile_selection.h"

namespace vegstream::terrain {

inline constexpr int kGridSide = kNodeQuads + 1;
inline constexpr uint32_t kGridVertices = static_cast<uint32_t>(kGridSide * kGridSide);
inline constexpr uint32_t kSkirtVertices = static_cast<uint32_t>(4 * kNodeQuads);

// Height data for a node: its own tile or one of its ancestors (asserted), never null.
struct HeightSource {
  const datasets::HeightTile* tile = nullptr;
};

struct NodeMeshOptions {
  // The surface drawn until now (an ancestor or the same tile): each vertex gets
  // morphDelta = coarse height − height, so the renderer can blend from it. nullopt: 0.
  std::optional<HeightSource> coarse;
  double minSkirtDepthM = 5.0;  // skirts are at least this deep
};

struct NodeMesh {
  TerrainMesh mesh;          // origin = the node's centre in ENU at the middle of its heights
  double skirtDepthM = 0.0;  // how far the skirt drops below each boundary vertex
  int sourceLevelsUp = 0;    // node.z − source tile z
};

// Bilinear height of `tile` at fractional tile coordinates of zoom z (x + fx, y + fy for a point
// of tile (z, x, y)); the point must lie in the tile's area or at most a pixel outside (clamped).
double sampleHeight(const datasets::HeightTile& tile, int z, double tileX, double tileY);

// Depth of the skirts of `node` drawn from a source `levelsUp` above it. Where two surfaces meet
// along an edge they are apart by at most the sum of their errors, and the skirt of the higher
// one must reach the lower one. So: at least minSkirtDepthM, at least 4 × the node's geometric
// error (a neighbour up to two levels coarser, which the screen-space bound makes the worst case
// in practice: the error halves per level while the distance changes little across one edge),
// and at least twice the error of the source's pixel spacing (a surface interpolated from a
// coarse ancestor next to one from finer data). buildNodeMesh adds the largest |morphDelta| on
// the boundary so that a morphing edge stays covered.
double skirtDepthM(const geo::TileId& node, int levelsUp, double minSkirtDepthM);

NodeMesh buildNodeMesh(const geo::TileId& node, const HeightSource& source, const geo::LocalFrame& frame,
                       const NodeMeshOptions& options = {});

}  // namespace vegstream::terrain
