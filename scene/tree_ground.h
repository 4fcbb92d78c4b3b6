#pragma once
// The ground the trees read (issue 20): a dataset's heights, imagery and NDVI mosaicked once at
// one zoom (streaming/dataset_snapshot.h), sampled at points of the scene's local ENU frame for
// vegetation::placeTreesInCells (vegetation/tree_placement.h). A pure function of the point and
// the dataset, never of what the streamer holds at the moment: the trees stay view-independent
// (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2), and a flight and `vegstream plants`
// that load the ground with the same limits get the same trees.
//
// A point (x, y) of the frame is taken to lie on the ground: its lat/lon is found at the ground's
// own height (ENU → geodetic at z = 0, the height there, then again at that height's z: over
// kilometres the frame's up tilts, so (x, y, 0) and (x, y, 2000 m) are metres apart on the
// ground), then
//   height   bilinear over the four mosaic pixels around it (Web Mercator pixel centres), z in the
//            frame of that ground point;
//   colour   each of the same four imagery pixels sRGB-decoded to linear, then bilinear (as
//            vegetation::sampleImageryLinear does within a tile);
//   NDVI     bilinear over the four pixels, those without NDVI dropped and the rest renormalised
//            (vegetation::sampleImageryNdvi); kNoNdvi where the dataset has none.
//   allowed  with allowLandcover (a dataset with a landcover layer): the species the class of the
//            mosaic pixel nearest the point allows (landcover_masks.h; classes are never blended);
//            every species otherwise.
// Invalid outside the mosaic's pixel centres, or where one of the four has no height or no imagery.

#include <cstddef>
#include <memory>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "geo/local_frame.h"
#include "scene/landcover_masks.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/tile_source.h"
#include "vegetation/tree_placement.h"

namespace vegstream::scene {

class TreeGround {
 public:
  // The ground mosaic's default size, the scene's default (SceneOptions::groundMaxPixels): at most
  // 4 Mpixels, so Zion's 34 × 43 km are read at zoom 12 (its finest, 30 m Landsat pixels).
  static constexpr uint64_t kDefaultMaxPixels = 4'000'000;
  static streaming::SnapshotLimits defaultLimits();

  // `imagery` on the same grid as `heights` (loadGroundImagery(…, heights)).
  TreeGround(streaming::HeightMosaic heights, streaming::ImageryMosaic imagery, const geo::LocalFrame& frame);

  // Both mosaics of the dataset at the finest zoom within `limits`. Errors as loadGroundHeights
  // and loadGroundImagery (a dataset without imagery: InvalidInput).
  static Result<TreeGround> load(streaming::TileSource& source, const datasets::DatasetMeta& meta,
                                 const geo::LocalFrame& frame, const streaming::SnapshotLimits& limits);

  // From now on (and in the callbacks at() gives after this), the species a sample allows follow
  // the landcover class under it; no effect when the mosaics hold no landcover.
  void allowLandcover(const LandcoverMasks& masks);

  vegetation::TreeGroundSample sample(double x, double y) const;
  // sample() as the placement's callback; it shares the mosaics, so it stays valid after this
  // object is moved or destroyed.
  vegetation::TreeGroundAt at() const;

  int zoom() const;
  double pixelM() const;  // Web Mercator metres per pixel (ground metres: × cos(latitude))
  size_t bytes() const;   // the mosaics' memory

 private:
  struct Data;
  std::shared_ptr<const Data> data_;
  std::shared_ptr<const LandcoverMasks> masks_;  // null: every species everywhere
};

}  // namespace vegstream::scene
