// Chunked level of detail (T. Ulrich, "Rendering Massive Terrains using Chunked Level of Detail
// Control", SIGGRAPH 2002 course notes) with a screen-space error metric: a quadtree of
// precomputed chunks (here: the dataset's XYZ tiles), each with a geometric error that halves
// per level; a chunk is drawn when its error projected to the screen,
//   ρ = ε · viewportHeightPx / (2 tan(fov/2) · d),
// is within the bound, d being the distance from the camera to the chunk's bounding box.
// Ulrich refines recursively; here refinement is worst-first from a priority queue so that a
// node budget cuts the least important refinement, not whichever the recursion reached last.

#include "terrain/tile_selection.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <queue>

#include <glm/geometric.hpp>

namespace vegstream::terrain {
namespace {

// Below this distance the projected error stops growing (the camera is inside the box).
constexpr double kMinDistanceM = 0.01;

// The frustum's side planes and the "in front of the camera" plane, as (a, b, c, d) with
// a·x + b·y + c·z + d ≥ 0 inside. Clip-space rows: x = row 0, y = row 1, w = row 3.
std::array<glm::dvec4, 5> frustumPlanes(const glm::dmat4& m) {
  auto row = [&m](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::dvec4 x = row(0), y = row(1), w = row(3);
  return {w + x, w - x, w + y, w - y, w};
}

bool outside(const NodeBox& b, const std::array<glm::dvec4, 5>& planes) {
  for (const glm::dvec4& p : planes) {
    // The box corner furthest along the plane normal: if even it is outside, all of the box is.
    const glm::dvec3 far{p.x >= 0.0 ? b.hi.x : b.lo.x, p.y >= 0.0 ? b.hi.y : b.lo.y, p.z >= 0.0 ? b.hi.z : b.lo.z};
    if (p.x * far.x + p.y * far.y + p.z * far.z + p.w < 0.0) return true;
  }
  return false;
}

double distanceToBox(const glm::dvec3& p, const NodeBox& b) {
  const glm::dvec3 d = glm::max(glm::max(b.lo - p, p - b.hi), glm::dvec3(0.0));
  return glm::length(d);
}

struct Candidate {
  geo::TileId id;
  double errorPx = 0.0;
  double distanceM = 0.0;
  bool refined = false;
};

// Heap order: larger error first, then nearer, then TileId — a total order, so deterministic.
bool lessUrgent(const Candidate& a, const Candidate& b) {
  if (a.errorPx != b.errorPx) return a.errorPx < b.errorPx;
  if (a.distanceM != b.distanceM) return a.distanceM > b.distanceM;
  return b.id < a.id;
}

bool covered(const std::vector<geo::TileRange>& ranges, const geo::TileId& t) {
  for (const geo::TileRange& r : ranges)
    if (r.contains(t)) return true;
  return false;
}

// A node's candidate: its box (from its resident heights where known; from the memo when given)
// tested against the view frustum; nullopt when culled.
struct NodeEvaluator {
  const SelectionView& view;
  const SelectionDataset& dataset;
  const geo::LocalFrame& frame;
  const TileHeightRange& heightRange;
  const std::array<glm::dvec4, 5>& planes;
  NodeBoxes* memo;

  std::optional<Candidate> evaluate(const geo::TileId& id) const {
    double hMin = dataset.minHeightM, hMax = dataset.maxHeightM;
    if (heightRange) {
      // A resident tile's own range is tighter; an empty or NaN range (all nodata) is ignored.
      if (const auto r = heightRange(id); r && r->first <= r->second) {
        hMin = static_cast<double>(r->first);
        hMax = static_cast<double>(r->second);
      }
    }
    NodeBox computed;
    const NodeBox& box = memo ? memo->at(id, hMin, hMax, frame) : (computed = nodeBox(id, hMin, hMax, frame));
    if (outside(box, planes)) return std::nullopt;
    const double d = distanceToBox(view.cameraEnu, box);
    return Candidate{id, projectedErrorPx(box.errorM, d, view), d, false};
  }
};

// The nodes not refined, sorted by id; the worst error among them.
void collectDrawn(const std::vector<Candidate>& nodes, Selection& selection) {
  for (const Candidate& c : nodes) {
    if (c.refined) continue;
    selection.nodes.push_back({c.id, c.errorPx, c.distanceM});
    selection.achievedErrorPx = std::max(selection.achievedErrorPx, c.errorPx);
  }
  std::sort(selection.nodes.begin(), selection.nodes.end(),
            [](const SelectedNode& a, const SelectedNode& b) { return a.id < b.id; });
}

}  // namespace

double projectedErrorPx(double errorM, double distanceM, const SelectionView& view) {
  assert(view.verticalFovRad > 0.0 && view.verticalFovRad < std::numbers::pi);
  const double d = std::max(distanceM, kMinDistanceM);
  return errorM * view.viewportHeightPx / (2.0 * std::tan(0.5 * view.verticalFovRad) * d);
}

Selection selectTiles(const SelectionView& view, const SelectionDataset& dataset, const geo::LocalFrame& frame,
                      const SelectionOptions& options, const TileHeightRange& heightRange, NodeBoxes* memo) {
  assert(0 <= dataset.minZoom && dataset.minZoom <= dataset.maxZoom && dataset.maxZoom <= geo::kMaxTileZoom);
  assert(dataset.minHeightM <= dataset.maxHeightM);
  assert(options.maxErrorPx > 0.0 && options.maxNodes >= 1);

  const std::array<glm::dvec4, 5> planes = frustumPlanes(view.viewProjection);
  // The tiles of each zoom that overlap the dataset (the same rule for roots and children).
  std::vector<std::vector<geo::TileRange>> coverage;
  for (int z = dataset.minZoom; z <= dataset.maxZoom; ++z)
    coverage.push_back(geo::tileRangesCovering(dataset.bounds, z));

  const NodeEvaluator evaluator{view, dataset, frame, heightRange, planes, memo};

  std::vector<Candidate> nodes;  // every node evaluated and kept; refined ones are not drawn
  auto heapLess = [&nodes](size_t a, size_t b) { return lessUrgent(nodes[a], nodes[b]); };
  std::priority_queue<size_t, std::vector<size_t>, decltype(heapLess)> queue(heapLess);
  auto refinable = [&](const Candidate& c) { return c.errorPx > options.maxErrorPx && c.id.z < dataset.maxZoom; };

  Selection selection;
  for (const geo::TileId& root : geo::tilesCovering(dataset.bounds, dataset.minZoom)) {
    if (auto c = evaluator.evaluate(root)) {
      nodes.push_back(*c);
      if (refinable(*c)) queue.push(nodes.size() - 1);
    }
  }
  size_t drawn = nodes.size();
  selection.budgetLimited = drawn > static_cast<size_t>(options.maxNodes);

  while (!selection.budgetLimited && !queue.empty()) {
    const size_t worst = queue.top();
    const geo::TileId id = nodes[worst].id;
    std::vector<Candidate> kids;
    for (const geo::TileId& child : geo::children(id)) {
      if (!covered(coverage[static_cast<size_t>(child.z - dataset.minZoom)], child)) continue;
      if (auto c = evaluator.evaluate(child)) kids.push_back(*c);
    }
    // Refining replaces one leaf by its visible children. If the most urgent refinement does
    // not fit, stop: every refinement left is less urgent than this one.
    if (drawn - 1 + kids.size() > static_cast<size_t>(options.maxNodes)) {
      selection.budgetLimited = true;
      break;
    }
    queue.pop();
    nodes[worst].refined = true;
    drawn = drawn - 1 + kids.size();
    for (const Candidate& k : kids) {
      nodes.push_back(k);
      if (refinable(k)) queue.push(nodes.size() - 1);
    }
  }

  collectDrawn(nodes, selection);
  assert(selection.nodes.size() == drawn);
  return selection;
}

std::vector<std::pair<geo::TileId, double>> wantedTiles(const Selection& selection) {
  std::vector<const SelectedNode*> order;
  order.reserve(selection.nodes.size());
  for (const SelectedNode& n : selection.nodes) order.push_back(&n);
  std::sort(order.begin(), order.end(), [](const SelectedNode* a, const SelectedNode* b) {
    if (a->projectedErrorPx != b->projectedErrorPx) return a->projectedErrorPx > b->projectedErrorPx;
    if (a->distanceM != b->distanceM) return a->distanceM < b->distanceM;
    return a->id < b->id;
  });
  std::vector<std::pair<geo::TileId, double>> wants;
  wants.reserve(order.size());
  for (const SelectedNode* n : order) wants.emplace_back(n->id, n->projectedErrorPx);
  return wants;
}

}  // namespace vegstream::terrain
