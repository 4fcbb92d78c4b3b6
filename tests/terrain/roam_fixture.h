#pragma once
// Every height tile of the Zion import (zion_tiles.h, max zoom 11) resident, with its wedgie
// table, behind a ResidentHeights lookup; and cameras over it. For the ROAM tests.

#include <map>
#include <memory>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "geo/local_frame.h"
#include "terrain/eye_space.h"
#include "terrain/resident_heights.h"
#include "terrain/roam_tessellator.h"
#include "terrain/wedgie_table.h"
#include "tests/terrain/zion_tiles.h"

namespace vegstream::terrain::test {

class ZionResident {
 public:
  ZionResident() {
    ZionTiles& z = ZionTiles::get();
    meta_ = z.meta();
    for (int zoom = meta_.minZoom; zoom <= meta_.maxZoom; ++zoom) {
      for (const geo::TileId& id : geo::tilesCovering(meta_.bounds, zoom)) {
        try {
          auto r = std::make_shared<streaming::ResidentTile>();
          r->key = {streaming::TileLayer::Height, id};
          r->heights = std::make_shared<const datasets::HeightTile>(z.tile(id));
          r->extra = std::make_shared<const WedgieTable>(*r->heights, meta_.minZoom);
          tiles_[id] = r;
        } catch (const std::exception&) {  // no tile written there
        }
      }
    }
    grid_ = gridForSeeds(meta_.minZoom, meta_.maxZoom, meta_.bounds.centre().y, SeedOptions{}.targetAreaM2);
    heights_ = std::make_unique<ResidentHeights>(grid_, [this](const geo::TileId& t) -> const streaming::ResidentTile* {
      for (geo::TileId a = t; a.z >= meta_.minZoom; a = geo::TileId{a.z - 1, a.x >> 1, a.y >> 1}) {
        auto it = tiles_.find(a);
        if (it != tiles_.end()) return it->second.get();
        if (a.z == 0) break;
      }
      return nullptr;
    });
    frame_ = std::make_unique<geo::LocalFrame>(
        geo::frameAtCentre(meta_.bounds, 0.5 * (meta_.minHeightM + meta_.maxHeightM)));
  }

  const datasets::DatasetMeta& meta() const { return meta_; }
  const BintreeGrid& grid() const { return grid_; }
  ResidentHeights& heights() { return *heights_; }
  const geo::LocalFrame& frame() const { return *frame_; }
  geo::TileRange roots() const { return geo::tileRangesCovering(meta_.bounds, meta_.minZoom).front(); }

  std::unique_ptr<RoamTessellator> tessellator(RoamOptions o = {}, SeedOptions s = {}, double fadeS = 0.0) {
    RoamMeshOptions mo;
    mo.fillHeightM = 0.5 * (meta_.minHeightM + meta_.maxHeightM);
    mo.fadeS = fadeS;
    return std::make_unique<RoamTessellator>(grid_, roots(), *frame_, *heights_, o, s, mo, meta_.bounds.centre().y);
  }

  // A 1920 × 1080 camera `aboveGround` metres over the ground at (lat, lon), heading (deg from
  // north, clockwise) and pitch (deg, negative looks down).
  EyeView camera(double latDeg, double lonDeg, double aboveGround, double headingDeg, double pitchDeg,
                 double widthPx = 1920.0, double heightPx = 1080.0) {
    const HeightSample g = heights_->sampleLonLat(latDeg, lonDeg);
    const double ground = g.heightM == g.heightM ? g.heightM : meta_.maxHeightM;
    const glm::dvec3 p = frame_->toLocal({latDeg, lonDeg, ground + aboveGround});
    const double h = glm::radians(headingDeg), pt = glm::radians(pitchDeg);
    const glm::dvec3 f{std::sin(h) * std::cos(pt), std::cos(h) * std::cos(pt), std::sin(pt)};
    return EyeView::lookAlong(p, f, {0.0, 0.0, 1.0}, glm::radians(60.0), widthPx, heightPx, 1.0);
  }

  // The pieces a frame would draw: every max-zoom tile of the dataset (the finest imagery).
  PieceSet finestPieces() const {
    PieceSet s;
    const std::vector<geo::TileId> t = geo::tilesCovering(meta_.bounds, meta_.maxZoom);
    s.assign(t);
    return s;
  }

 private:
  datasets::DatasetMeta meta_;
  std::map<geo::TileId, std::shared_ptr<streaming::ResidentTile>> tiles_;
  BintreeGrid grid_;
  std::unique_ptr<ResidentHeights> heights_;
  std::unique_ptr<geo::LocalFrame> frame_;
};

// Updates until nothing more splits or merges (at most `frames` frames); the frames it took.
inline int converge(RoamTessellator& r, const EyeView& view, const PieceSet& pieces, int frames = 40) {
  for (int i = 0; i < frames; ++i) {
    r.update(view, pieces, 0.0);
    if (r.figures().splits == 0 && r.figures().merges == 0) return i;
  }
  return frames;
}

inline ZionResident& zionResident() {
  static ZionResident r;
  return r;
}

}  // namespace vegstream::terrain::test
