// One chunk of the chunked-LOD terrain (tile_selection.cpp): a regular grid over the node's
// Web Mercator square, heights from the nearest resident tile, skirts against cracks, and the
// coarse surface's heights for geomorphing (Ulrich 2002 morphs each chunk from its parent's
// surface; here from whatever was drawn before the finer data arrived).

#include "terrain/tile_node_mesh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

namespace vegstream::terrain {
namespace {

// Grid vertices plus a ring of one quad around them, so that normals on the node's edge come
// from central differences over the same heights its neighbour sees (when the source is shared).
constexpr int kRing = kGridSide + 2;

size_t ringIndex(int i, int j) {  // i, j in [-1, kGridSide]
  return static_cast<size_t>(j + 1) * static_cast<size_t>(kRing) + static_cast<size_t>(i + 1);
}
uint32_t gridIndex(int i, int j) { return static_cast<uint32_t>(j * kGridSide + i); }

[[maybe_unused]] bool isAncestorOrSelf(const geo::TileId& a, const geo::TileId& node) {
  if (a.z > node.z) return false;
  const int shift = node.z - a.z;
  return (node.x >> shift) == a.x && (node.y >> shift) == a.y;
}

// The boundary of the grid walked clockwise from above, starting at the north-west corner.
std::array<uint32_t, kSkirtVertices> boundary() {
  std::array<uint32_t, kSkirtVertices> b{};
  size_t k = 0;
  for (int i = 0; i < kNodeQuads; ++i) b[k++] = gridIndex(i, 0);                  // north, W → E
  for (int j = 0; j < kNodeQuads; ++j) b[k++] = gridIndex(kNodeQuads, j);         // east, N → S
  for (int i = kNodeQuads; i > 0; --i) b[k++] = gridIndex(i, kNodeQuads);         // south, E → W
  for (int j = kNodeQuads; j > 0; --j) b[k++] = gridIndex(0, j);                  // west, S → N
  assert(k == kSkirtVertices);
  return b;
}

}  // namespace

double sampleHeight(const datasets::HeightTile& tile, int z, double tileX, double tileY) {
  assert(tile.size > 0 && tile.heights.size() == static_cast<size_t>(tile.size) * static_cast<size_t>(tile.size));
  assert(tile.id.z <= z);
  // Into the tile's pixel space: zoom z tile coordinates shrink by 2 per level up.
  const double scale = std::ldexp(1.0, tile.id.z - z);
  const double n = static_cast<double>(tile.size);
  // Pixel (i, j) is centred at (i + 0.5, j + 0.5); clamp to the outermost centres.
  const double gx = std::clamp((tileX * scale - tile.id.x) * n - 0.5, 0.0, n - 1.0);
  const double gy = std::clamp((tileY * scale - tile.id.y) * n - 0.5, 0.0, n - 1.0);
  const int x0 = static_cast<int>(gx), y0 = static_cast<int>(gy);
  const double fx = gx - x0, fy = gy - y0;
  const int x1 = std::min(x0 + 1, tile.size - 1), y1 = std::min(y0 + 1, tile.size - 1);
  // A neighbour with zero weight is not read, so a sample exactly on a pixel centre next to
  // nodata is still valid; any other nodata neighbour makes the result NaN.
  auto row = [&](int y) {
    const double a = static_cast<double>(tile.at(x0, y));
    return fx == 0.0 ? a : a * (1.0 - fx) + static_cast<double>(tile.at(x1, y)) * fx;
  };
  const double top = row(y0);
  return fy == 0.0 ? top : top * (1.0 - fy) + row(y1) * fy;
}

double skirtDepthM(const geo::TileId& node, int levelsUp, double minSkirtDepthM) {
  assert(levelsUp >= 0);
  // The source's pixel: 256 pixels per tile side against kNodeQuads quads, levelsUp levels up.
  const double sourcePixelM = nodeQuadSizeM(node) * kNodeQuads / datasets::kTileSize * std::ldexp(1.0, levelsUp);
  return std::max({minSkirtDepthM, 4.0 * nodeGeometricErrorM(node), 2.0 * kErrorPerQuad * sourcePixelM});
}

NodeMesh buildNodeMesh(const geo::TileId& node, const HeightSource& source, const geo::LocalFrame& frame,
                       const NodeMeshOptions& options) {
  assert(geo::isValid(node));
  assert(source.tile != nullptr && isAncestorOrSelf(source.tile->id, node));
  assert(!options.coarse || (options.coarse->tile != nullptr && isAncestorOrSelf(options.coarse->tile->id, node)));

  NodeMesh out;
  out.sourceLevelsUp = node.z - source.tile->id.z;
  TerrainMesh& mesh = out.mesh;

  // Longitude depends only on the column and latitude only on the row (Web Mercator is a
  // cylindrical projection), so they are computed once per column and row.
  std::array<double, kRing> lon{}, lat{};
  for (int k = -1; k <= kGridSide; ++k) {
    const double f = static_cast<double>(k) / kNodeQuads;
    lon[static_cast<size_t>(k + 1)] = geo::tileXYToLonLat({node.x + f, node.y}, node.z).x;
    lat[static_cast<size_t>(k + 1)] = geo::tileXYToLonLat({node.x, node.y + f}, node.z).y;
  }

  std::vector<double> height(static_cast<size_t>(kRing) * kRing);
  double hMin = std::numeric_limits<double>::max(), hMax = std::numeric_limits<double>::lowest();
  for (int j = -1; j <= kGridSide; ++j) {
    for (int i = -1; i <= kGridSide; ++i) {
      const double h = sampleHeight(*source.tile, node.z, node.x + static_cast<double>(i) / kNodeQuads,
                                    node.y + static_cast<double>(j) / kNodeQuads);
      height[ringIndex(i, j)] = h;
      const bool onGrid = i >= 0 && i < kGridSide && j >= 0 && j < kGridSide;
      if (onGrid && !std::isnan(h)) {
        hMin = std::min(hMin, h);
        hMax = std::max(hMax, h);
      }
    }
  }
  const double midHeight = hMin <= hMax ? 0.5 * (hMin + hMax) : 0.0;
  mesh.origin = frame.toLocal({lat[static_cast<size_t>(kRing / 2)], lon[static_cast<size_t>(kRing / 2)], midHeight});

  // Double positions of the grid and its ring; nodata samples sit at height 0 and are never
  // used by a triangle or a normal.
  std::vector<glm::dvec3> position(height.size());
  for (int j = -1; j <= kGridSide; ++j) {
    for (int i = -1; i <= kGridSide; ++i) {
      const double h = height[ringIndex(i, j)];
      position[ringIndex(i, j)] =
          frame.toLocal({lat[static_cast<size_t>(j + 1)], lon[static_cast<size_t>(i + 1)], std::isnan(h) ? 0.0 : h});
    }
  }

  mesh.vertices.resize(kGridVertices + kSkirtVertices);
  for (int j = 0; j < kGridSide; ++j) {
    for (int i = 0; i < kGridSide; ++i) {
      const size_t r = ringIndex(i, j);
      TerrainVertex& v = mesh.vertices[gridIndex(i, j)];
      const double h = height[r];
      v.position = glm::vec3(position[r] - mesh.origin);
      v.heightMsl = static_cast<float>(std::isnan(h) ? 0.0 : h);
      v.uv = glm::vec2(static_cast<float>(i) / kNodeQuads, static_cast<float>(j) / kNodeQuads);
      // Central differences in ENU; a nodata neighbour is replaced by the vertex itself.
      auto pick = [&](int ii, int jj) {
        const size_t q = ringIndex(ii, jj);
        return std::isnan(height[q]) ? position[r] : position[q];
      };
      const glm::dvec3 east = pick(i + 1, j) - pick(i - 1, j);
      const glm::dvec3 south = pick(i, j + 1) - pick(i, j - 1);  // rows run north → south
      const glm::dvec3 n = glm::cross(south, east);
      const double len = glm::length(n);
      v.normal = len > 0.0 ? glm::vec3(n / len) : glm::vec3(frame.upAt({lat[static_cast<size_t>(j + 1)], lon[static_cast<size_t>(i + 1)], 0.0}));
      v.morphDelta = 0.0f;
      if (options.coarse && !std::isnan(h)) {
        const double c = sampleHeight(*options.coarse->tile, node.z, node.x + static_cast<double>(i) / kNodeQuads,
                                      node.y + static_cast<double>(j) / kNodeQuads);
        // Where the coarse surface had no data there is nothing to morph from: appear in place.
        if (!std::isnan(c)) v.morphDelta = static_cast<float>(c - h);
      }
    }
  }

  // Skirts: deep enough for the errors on either side of the edge, plus any morph offset.
  const std::array<uint32_t, kSkirtVertices> edge = boundary();
  double maxMorph = 0.0;
  for (const uint32_t b : edge) maxMorph = std::max(maxMorph, std::abs(static_cast<double>(mesh.vertices[b].morphDelta)));
  out.skirtDepthM = skirtDepthM(node, out.sourceLevelsUp, options.minSkirtDepthM) + maxMorph;
  for (size_t k = 0; k < edge.size(); ++k) {
    const int i = static_cast<int>(edge[k]) % kGridSide, j = static_cast<int>(edge[k]) / kGridSide;
    const double h = height[ringIndex(i, j)];
    TerrainVertex& s = mesh.vertices[kGridVertices + k];
    s = mesh.vertices[edge[k]];  // same normal, uv, colour height and morph as the edge above it
    const glm::dvec3 p = frame.toLocal(
        {lat[static_cast<size_t>(j + 1)], lon[static_cast<size_t>(i + 1)], (std::isnan(h) ? 0.0 : h) - out.skirtDepthM});
    s.position = glm::vec3(p - mesh.origin);
  }

  auto valid = [&](uint32_t g) {
    const int i = static_cast<int>(g) % kGridSide, j = static_cast<int>(g) / kGridSide;
    return !std::isnan(height[ringIndex(i, j)]);
  };
  mesh.indices.reserve(static_cast<size_t>(kNodeQuads) * kNodeQuads * 6 + kSkirtVertices * 6);
  for (int j = 0; j < kNodeQuads; ++j) {
    for (int i = 0; i < kNodeQuads; ++i) {
      const uint32_t nw = gridIndex(i, j), ne = gridIndex(i + 1, j), sw = gridIndex(i, j + 1), se = gridIndex(i + 1, j + 1);
      // Counter-clockwise seen from above (east = +x, north = +y), as buildGridMesh.
      if (valid(sw) && valid(se) && valid(nw)) mesh.indices.insert(mesh.indices.end(), {sw, se, nw});
      if (valid(se) && valid(ne) && valid(nw)) mesh.indices.insert(mesh.indices.end(), {se, ne, nw});
    }
  }
  // Walking the boundary clockwise from above, the node lies to the right, so (a, b, a') and
  // (b, b', a') face outwards.
  for (size_t k = 0; k < edge.size(); ++k) {
    const size_t k1 = (k + 1) % edge.size();
    if (!valid(edge[k]) || !valid(edge[k1])) continue;
    const uint32_t a = edge[k], b = edge[k1];
    const uint32_t as = kGridVertices + static_cast<uint32_t>(k), bs = kGridVertices + static_cast<uint32_t>(k1);
    mesh.indices.insert(mesh.indices.end(), {a, b, as, b, bs, as});
  }
  return out;
}

}  // namespace vegstream::terrain
