// Nested wedgie thicknesses per height tile (wedgie_table.h). Seed 001_3eca9f2c7752e4fb.txt
// §3.1 builds on ROAM (Duchaineau et al. 1997); the nested bound is ROAM's §5 "wedgies".

#include "terrain/wedgie_table.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrain/bintree.h"

namespace vegstream::terrain {
namespace {

constexpr int kSide = geo::kDefaultTileSize;
constexpr int kCorners = kSide + 1;
constexpr double kEarthCircumferenceM = 40075016.685578488;

// Entries of levels [0, level): a level-2k level has 2·4^k halves, a level-2k+1 one 4·4^k quarters.
size_t levelOffset(int level) {
  size_t n = 0;
  for (int l = 0; l < level; ++l) n += size_t{(l % 2 == 0) ? 2u : 4u} << (2 * (l / 2));
  return n;
}

struct Acc {
  float e = kNoData;
  bool any = false;       // data somewhere under the triangle
  bool complete = false;  // data everywhere under it
};

// Corner heights of a tile: the bilinear surface at pixel corners = the mean of the (up to)
// four pixels around the corner, clamped at the tile's edge; nodata if any of them is.
float cornerHeight(const datasets::HeightTile& tile, uint32_t i, uint32_t j) {
  const int x0 = std::max(int(i) - 1, 0), x1 = std::min(int(i), kSide - 1);
  const int y0 = std::max(int(j) - 1, 0), y1 = std::min(int(j), kSide - 1);
  return 0.25f * (tile.at(x0, y0) + tile.at(x1, y0) + tile.at(x0, y1) + tile.at(x1, y1));
}

double pixelGroundM(const geo::TileId& id) {
  const double latDeg = geo::tileXYToLonLat({id.x + 0.5, id.y + 0.5}, id.z).y;
  return kEarthCircumferenceM / (geo::tilesPerSide(id.z) * kSide) * std::cos(latDeg * M_PI / 180.0);
}

// The nested thickness of a tile-bintree triangle (pixel-corner coordinates) from its corner
// heights, calling store(t, level, e) for every triangle of its subtree down to the pixels.
template <typename Heights, typename Store>
Acc nested(const TriCorners& t, int level, const Heights& h, double pixelM, const Store& store) {
  const float ha = h(t.apex), hl = h(t.left), hr = h(t.right);
  const bool cornersOk = !std::isnan(ha) && !std::isnan(hl) && !std::isnan(hr);
  // Only where data is missing under it (a square root per triangle otherwise unused).
  const auto partialE = [&] {
    const double dx = double(t.left.x) - double(t.right.x), dy = double(t.left.y) - double(t.right.y);
    return static_cast<float>(0.5 * std::sqrt(dx * dx + dy * dy) * pixelM);
  };
  Acc out;
  if (level == kTileLevels) {
    // Half a pixel square: the bilinear surface departs most from the plane at the pixel centre.
    const GridPoint opposite{t.left.x + t.right.x - t.apex.x, t.left.y + t.right.y - t.apex.y};
    const float ho = h(opposite);
    out.complete = cornersOk && !std::isnan(ho);
    out.any = !std::isnan(ha) || !std::isnan(hl) || !std::isnan(hr);
    if (out.complete)
      out.e = std::abs(0.25f * (ha + hl + hr + ho) - 0.5f * (hl + hr));
    else
      out.e = out.any ? partialE() : kNoData;
  } else {
    const Acc c0 = nested(child(t, 0), level + 1, h, pixelM, store);
    const Acc c1 = nested(child(t, 1), level + 1, h, pixelM, store);
    const float hm = h(midpoint(t.left, t.right));
    const float below = std::max({c0.e, c1.e, 0.0f});
    out.any = c0.any || c1.any;
    out.complete = c0.complete && c1.complete && cornersOk && !std::isnan(hm);
    if (out.complete)
      out.e = std::abs(hm - 0.5f * (hl + hr)) + below;
    else
      out.e = out.any ? std::max(below, partialE()) : kNoData;
  }
  store(t, level, out.e);
  return out;
}

}  // namespace

WedgieTable::WedgieTable(const datasets::HeightTile& tile, int rootZoom) : tile_(tile.id), rootZoom_(rootZoom) {
  assert(tile.id.z >= rootZoom && tile.size == kSide);
  errors_.assign(levelOffset(kStoredLevels + 1), kNoData);
  std::vector<float> corners(size_t{kCorners} * kCorners);
  for (uint32_t j = 0; j < uint32_t(kCorners); ++j)
    for (uint32_t i = 0; i < uint32_t(kCorners); ++i) corners[size_t(j) * kCorners + i] = cornerHeight(tile, i, j);
  auto h = [&](GridPoint p) { return corners[size_t(p.y) * kCorners + size_t(p.x)]; };
  auto store = [&](const TriCorners& t, int level, float e) {
    if (level > kStoredLevels) return;
    const glm::dvec2 c{(double(t.apex.x) + t.left.x + t.right.x) / 3.0,
                       (double(t.apex.y) + t.left.y + t.right.y) / 3.0};
    errors_[thicknessIndex(level, c)] = e;
  };
  pixelM_ = pixelGroundM(tile.id);
  const GridPoint nw{0, 0}, ne{kSide, 0}, se{kSide, kSide}, sw{0, kSide};
  const bool swne = tile.id.z > rootZoom && ((tile.id.x + tile.id.y) & 1) != 0;
  if (swne) {
    nested(TriCorners{nw, sw, ne}, 0, h, pixelM_, store);
    nested(TriCorners{se, ne, sw}, 0, h, pixelM_, store);
  } else {
    nested(TriCorners{sw, se, nw}, 0, h, pixelM_, store);
    nested(TriCorners{ne, nw, se}, 0, h, pixelM_, store);
  }
}

float WedgieTable::deepThickness(const datasets::HeightTile& tile, const TriCorners& cornersPx, int level) const {
  assert(level > kStoredLevels && level <= kTileLevels && tile.id == tile_);
  auto h = [&](GridPoint p) { return cornerHeight(tile, p.x, p.y); };
  return nested(cornersPx, level, h, pixelM_, [](const TriCorners&, int, float) {}).e;
}

size_t WedgieTable::thicknessIndex(int level, glm::dvec2 c) const {
  assert(level >= 0 && level <= kStoredLevels);
  const int k = level / 2;
  const double side = double(kSide >> k);
  const int n = 1 << k;
  const int qx = std::clamp(static_cast<int>(c.x / side), 0, n - 1);
  const int qy = std::clamp(static_cast<int>(c.y / side), 0, n - 1);
  const double u = c.x / side - qx, v = c.y / side - qy;
  int part = 0;
  if (level % 2 == 0) {
    const int z = tile_.z + k;
    const long long gx = (long long)(tile_.x) * n + qx, gy = (long long)(tile_.y) * n + qy;
    const bool swne = z > rootZoom_ && ((gx + gy) & 1) != 0;
    part = swne ? (u + v < 1.0 ? 0 : 1) : (v > u ? 0 : 1);
  } else {
    const double du = u - 0.5, dv = v - 0.5;
    part = std::abs(du) > std::abs(dv) ? (du > 0 ? 1 : 3) : (dv < 0 ? 0 : 2);
  }
  const size_t parts = level % 2 == 0 ? 2 : 4;
  return levelOffset(level) + (size_t(qy) * size_t(n) + size_t(qx)) * parts + size_t(part);
}

float WedgieTable::thickness(int level, glm::dvec2 centroidPx) const {
  // Deeper than stored: the stored ancestor's thickness bounds it (nesting).
  return errors_[thicknessIndex(std::min(level, kStoredLevels), centroidPx)];
}

streaming::HeightExtraFn wedgieTableBuilder(int rootZoom) {
  return [rootZoom](const datasets::HeightTile& tile) -> std::shared_ptr<const streaming::TileExtra> {
    if (tile.id.z < rootZoom || tile.size != kSide) return nullptr;
    return std::make_shared<const WedgieTable>(tile, rootZoom);
  };
}

uint64_t wedgieTableBytes() { return levelOffset(kStoredLevels + 1) * sizeof(float) + sizeof(WedgieTable); }

}  // namespace vegstream::terrain
