#pragma once
// Which tiles the terrain streams and draws as pieces this frame, and at which level: chunked
// level of detail over the XYZ Web Mercator pyramid of one dataset (Ulrich 2002). Every node of
// the quadtree is one XYZ tile, whose error is modelled as a (kNodeQuads + 1)² grid over it; a
// node is refined into its four children while that error, projected to the screen, exceeds the
// bound. The streamed terrain wants the selected nodes' tiles and draws ROAM's triangles over
// them (streamed_terrain.h): the selection decides which data is fine enough, not the triangles.
//
// Contract:
//   - The drawn leaves never overlap (no leaf is an ancestor of another) and together cover the
//     part of the dataset that is in view: a node is left out only when its conservative box is
//     outside the view frustum (or, refined, when all its children are).
//   - A drawn leaf's projected error is ≤ maxErrorPx unless it is at maxZoom or the selection
//     is budgetLimited.
//   - At most maxNodes leaves are drawn (unless the visible minZoom tiles alone are more: they
//     are all drawn, and budgetLimited is set). Refinement goes worst-first, so when the budget
//     runs out it is the least important refinements that are not made.
//   - Deterministic: the same input gives the same output, in the same order.
//
// Frustum convention: any perspective (or orthographic) ENU → clip matrix, with either handedness
// of y and any depth convention (OpenGL [-1, 1], Vulkan [0, 1], reverse-Z, infinite far plane):
// only the clip x, y and w rows are used, as the planes |x| ≤ w, |y| ≤ w and w ≥ 0 (in front of
// the camera). There is no near or far plane test, so depth conventions cannot matter.

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "geo/bounds.h"
#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"
#include "terrain/node_boxes.h"

namespace vegstream::terrain {

// Quads along one side of a node's error model: a 256-pixel tile sampled every 8 pixels.
inline constexpr int kNodeQuads = 32;
// Selections that should reach one quad per data pixel pass SelectionDataset::maxZoom = the
// dataset's max zoom + kLevelsBeyondData (= log2(256 / kNodeQuads)); the streamed terrain stops
// at the data's max zoom (ROAM refines below a tile by itself).
inline constexpr int kLevelsBeyondData = 3;
static_assert(kNodeQuads << kLevelsBeyondData == geo::kDefaultTileSize);

// Geometric error of a node = kErrorPerQuad × the ground size of one of its mesh quads. Why 0.5:
// between two vertices s apart, a feature whose slopes stay within 45° (a tent-shaped ridge or
// gully between the samples) departs from the straight chord by at most s/2 · tan 45° = s/2.
// Smooth terrain is far better than that (Cesium takes 0.25 of a heightmap sample); cliffs
// steeper than 45° (Zion's walls) locally exceed it, which the budget of a few pixels absorbs.
inline constexpr double kErrorPerQuad = 0.5;

struct SelectionView {
  glm::dvec3 cameraEnu{0.0};       // camera position in the dataset's local ENU frame, metres
  glm::dmat4 viewProjection{1.0};  // ENU → clip; only used for the frustum planes (see above)
  double viewportHeightPx = 1080.0;
  double verticalFovRad = 1.0;
};

// What the selection needs to know about the dataset.
struct SelectionDataset {
  geo::GeoBounds bounds;  // extent of the data (not crossing the antimeridian)
  int minZoom = 0;
  int maxZoom = 0;  // deepest node level (≥ the data's max zoom, see kLevelsBeyondData)
  double minHeightM = 0.0;
  double maxHeightM = 0.0;
};

struct SelectionOptions {
  double maxErrorPx = 2.0;  // screen-space error bound
  int maxNodes = 512;       // most leaves drawn
};

// Height range (min, max metres) of the heights a node will be drawn with, when known (e.g. its
// tile or the ancestor it is drawn from is resident); nullopt: the dataset's range is used.
using TileHeightRange = std::function<std::optional<std::pair<float, float>>(const geo::TileId&)>;

struct SelectedNode {
  geo::TileId id;  // the node: its mesh covers this XYZ tile's square
  double projectedErrorPx = 0.0;
  double distanceM = 0.0;  // camera to the node's bounding box (0 inside it)
};

struct Selection {
  std::vector<SelectedNode> nodes;  // the leaves to draw, sorted by TileId
  double achievedErrorPx = 0.0;     // max projected error over the drawn leaves
  bool budgetLimited = false;       // a wanted refinement did not fit maxNodes
};

// Ground size (metres) of one mesh quad of the node, east-west at the node's latitude nearest
// the equator (the largest quad in the node), and the node's geometric error.
double nodeQuadSizeM(const geo::TileId& node);
double nodeGeometricErrorM(const geo::TileId& node);

// error · viewportHeightPx / (2 tan(fov/2) · distance); distances below 1 cm count as 1 cm.
double projectedErrorPx(double errorM, double distanceM, const SelectionView& view);

// `memo` (optional, node_boxes.h) keeps the nodes' boxes from one selection to the next in the
// same frame; the selection is the same, bit for bit, with or without it.
Selection selectTiles(const SelectionView& view, const SelectionDataset& dataset, const geo::LocalFrame& frame,
                      const SelectionOptions& options = {}, const TileHeightRange& heightRange = {},
                      NodeBoxes* memo = nullptr);

// The drawn nodes' tiles, most urgent first: priority = projected error in px (larger = more
// urgent); on equal priority the nearer node comes first, then TileId order. Nodes deeper than
// the dataset's max zoom (see kLevelsBeyondData) are listed as they are: the caller maps them
// to their max-zoom ancestor.
std::vector<std::pair<geo::TileId, double>> wantedTiles(const Selection& selection);

}  // namespace vegstream::terrain
