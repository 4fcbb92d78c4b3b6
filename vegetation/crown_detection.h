#pragma once
// Individual trees from a canopy height model (issue 41 item 3): local maxima of the smoothed
// CHM found with a window whose size grows with the height, after
//   S. C. Popescu and R. H. Wynne, "Seeing the trees in the forest: using lidar and multispectral
//   data fusion with local filtering and variable window size for estimating tree height",
//   Photogrammetric Engineering & Remote Sensing 70(5), 589–604, 2004 — §"Local filtering with
//   variable window size": the window's diameter is the crown width a height predicts (their
//   regression for pines and deciduous trees together, CW = 2.51503 + 0.00901 h², metres), the
//   CHM smoothed by a small low-pass (3 × 3) first, a pixel a tree top when no pixel of its
//   circular window is higher.
//
// Contract:
//   input   a raster of heights above ground (metres, row-major, NaN = no data), square pixels of
//           pixelM ground metres. Rows and columns have no orientation requirement.
//   smooth  a 3 × 3 binomial (1 2 1 / 2 4 2 / 1 2 1) over the valid neighbours within 1 m of the
//           centre (edge-preserving: a tall crown's edge does not leak into a small one beside it).
//   tops    a pixel of smoothed height ≥ minHeightM whose window (a disc of radius
//           windowRadiusM(h), h its smoothed height) holds no higher smoothed pixel on its own
//           crown; among equal heights the pixel first in row-major order wins, so a flat top
//           yields one tree. Our refinement of the fixed window: a higher pixel whose straight way
//           from the top dips more than 0.3 m below the top stands on another crown (a small tree
//           on a big one's shoulder is kept; noise after the smoothing is ~0.06 m).
//   position  the top pixel's centre moved by a parabola through its 3 × 3 smoothed neighbours
//           (at most half a pixel each way): (col + 0.5 + dx, row + 0.5 + dy) in the raster's
//           continuous pixel coordinates.
//   height  the highest raw sample of the 3 × 3 around the top (the smoothing lowers peaks).
//   crown   radius: the mean over 8 directions of the distance walked down from the top on the
//           raw CHM until the next sample rises (a neighbour's crown), falls below
//           kCrownFloor × height or below minHeightM, or is no data; clamped to
//           [pixelM, windowRadiusM(height)·2].
// Deterministic and local: a tree depends only on the pixels within windowRadiusM(maxHeightM) +
// 2 pixels of it (marginPixels), so detecting on any window that holds that margin around a
// point finds the same trees there (the caller keeps the trees of its own area: scene glue).

#include <cstdint>
#include <span>
#include <vector>

namespace vegstream::vegetation {

struct CrownDetectionOptions {
  float pixelM = 1.0f;          // ground metres per pixel (> 0)
  float minHeightM = 2.0f;      // lower smoothed tops are not trees
  float maxHeightM = 130.0f;    // the window reaches no farther than this height's radius
  float windowScale = 0.5f;     // the window's diameter as a share of Popescu–Wynne's crown width
  float minWindowM = 1.0f;      // radius bounds of the window, metres
  float maxWindowM = 8.0f;
};

inline constexpr float kCrownFloor = 0.35f;  // a crown's edge: below this share of the tree's height

struct DetectedCrown {
  double col = 0.0, row = 0.0;  // continuous pixel coordinates (pixel (i, j) spans [i, i + 1))
  float heightM = 0.0f;
  float crownRadiusM = 0.0f;
};

// Popescu & Wynne's crown width at height h (metres), the window's diameter before windowScale.
float popescuWynneCrownWidthM(float heightM);
// The window's radius at smoothed height h: clamp(windowScale · CW(h) / 2, minWindowM, maxWindowM).
float windowRadiusM(const CrownDetectionOptions& o, float heightM);
// Pixels a caller must read around its area so that detection there is exact (see above).
int marginPixels(const CrownDetectionOptions& o);

// The tree tops of a width × height raster (heights.size() == width · height), row-major order
// of their top pixel.
std::vector<DetectedCrown> detectCrowns(std::span<const float> heights, int width, int height,
                                        const CrownDetectionOptions& options);

}  // namespace vegstream::vegetation
