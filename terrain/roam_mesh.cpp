// The ROAM bintree (roam_mesh.h): Duchaineau et al. 1997 §4 (split, forced split, merge of
// diamonds), as used by seed 001_3eca9f2c7752e4fb.txt §3.1.

#include "terrain/roam_mesh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::terrain {
namespace {

constexpr double kEarthRadiusM = 6371000.0;

double smooth(double s) { return s * s * (3.0 - 2.0 * s); }

}  // namespace

double morphedHeight(double heightM, double fromHeightM, double toHeightM, double morphStartS, double t, double fadeS) {
  if (!(heightM == heightM)) return heightM;
  const double to = toHeightM == toHeightM ? toHeightM : heightM;
  if (!(fromHeightM == fromHeightM) || fadeS <= 0.0) return to;
  const double s = std::clamp((t - morphStartS) / fadeS, 0.0, 1.0);
  return fromHeightM + (to - fromHeightM) * smooth(s);
}

double RoamVertex::drawnHeight(double t, double fadeS) const {
  return morphedHeight(heightM, fromHeightM, toHeightM, morphStartS, t, fadeS);
}

RoamMesh::RoamMesh(BintreeGrid grid, geo::TileRange roots, const geo::LocalFrame& frame, ResidentHeights& heights,
                   RoamMeshOptions options)
    : grid_(grid), frame_(frame), heights_(&heights), options_(options) {
  assert(roots.z == grid.rootZoom() && roots.count() > 0);
  const int nx = roots.maxX - roots.minX + 1, ny = roots.maxY - roots.minY + 1;
  const uint32_t s = 1u << (grid.gridZoom() - grid.rootZoom());
  auto cornerAt = [&](int i, int j) { return cornerVertices_[size_t(j) * size_t(nx + 1) + size_t(i)]; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      cornerVertices_.push_back(newVertex({uint32_t(roots.minX + i) * s, uint32_t(roots.minY + j) * s},
                                          std::numeric_limits<double>::quiet_NaN()));
  auto pairAt = [&](int i, int j) { return uint32_t(2 * (j * nx + i)); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const uint32_t p = allocPair();
      assert(p == pairAt(i, j));
      RoamNode& t0 = nodes_[p];
      RoamNode& t1 = nodes_[p + 1];
      const uint32_t nw = cornerAt(i, j), ne = cornerAt(i + 1, j), se = cornerAt(i + 1, j + 1), sw = cornerAt(i, j + 1);
      t0.path = {roots.minX + i, roots.minY + j, 0, 0, 0};
      t1.path = {roots.minX + i, roots.minY + j, 1, 0, 0};
      t0.v[0] = sw;
      t0.v[1] = se;
      t0.v[2] = nw;
      t1.v[0] = ne;
      t1.v[1] = nw;
      t1.v[2] = se;
      t0.base = p + 1;
      t1.base = p;
      t0.left = j + 1 < ny ? pairAt(i, j + 1) + 1 : kNoNode;  // south edge: the southern tile's tree 1
      t0.right = i > 0 ? pairAt(i - 1, j) + 1 : kNoNode;      // west edge: the western tile's tree 1
      t1.left = j > 0 ? pairAt(i, j - 1) : kNoNode;           // north edge: the northern tile's tree 0
      t1.right = i + 1 < nx ? pairAt(i + 1, j) : kNoNode;     // east edge: the eastern tile's tree 0
      roots_.push_back(p);
      roots_.push_back(p + 1);
    }
  }
  leaves_ = roots_.size();
  for (uint32_t r : roots_) {
    nodes_[r].thickness = thicknessOf(r);
    updateRadius(r);
  }
}

namespace {
// Reserves n and writes every element of the capacity once: the pages are faulted in here, not
// inside the frames that grow the mesh (a fast descent adds 1 500 nodes a frame, and their
// first-touch faults were a tenth of its split phase).
template <class T>
void reserveTouched(std::vector<T>& pool, size_t n) {
  pool.reserve(n);
  const size_t used = pool.size();
  pool.resize(pool.capacity());
  pool.resize(used);
}
}  // namespace

void RoamMesh::reserve(uint64_t leaves) {
  // A bintree of L leaves has 2L − 1 nodes per root and about L / 2 vertices.
  const size_t nodes = size_t(2 * leaves + roots_.size()), vertices = size_t(leaves / 2 + leaves / 8 + cornerVertices_.size());
  reserveTouched(nodes_, nodes);
  reserveTouched(vertices_, vertices);
  // The compactions' copies go into these (beginCompaction): faulted in there, the first copies
  // ran slower, and the next update waits for a copy (H200, benchmark-30s: the waits summed
  // 5.1 and 4.0 ms over the flight, 2.1 and 2.0 with these touched here; the longest
  // 1.8 → 0.4 ms at t = 2.3 s).
  reserveTouched(spareNodes_, nodes);
  reserveTouched(spareVertices_, vertices);
}

uint32_t RoamMesh::allocPair() {
  ++pairsAllocated_;
  if (!freePairs_.empty()) {
    const uint32_t p = freePairs_.back();
    freePairs_.pop_back();
    nodes_[p] = RoamNode{};
    nodes_[p + 1] = RoamNode{};
    return p;
  }
  const auto p = static_cast<uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  return p;
}

void RoamMesh::freePair(uint32_t first) {
  for (uint32_t i = first; i < first + 2; ++i)
    if (nodes_[i].drawnChunk != kNoNode) releasedChunks_.push_back(nodes_[i].drawnChunk);
  nodes_[first] = RoamNode{};
  nodes_[first + 1] = RoamNode{};
  nodes_[first].path.level = nodes_[first + 1].path.level = 0xFF;  // matches no queued path
  freePairs_.push_back(first);
}

void RoamMesh::sampleVertex(RoamVertex& v, bool morph) { applySample(v, heights_->sample(v.grid), morph); }

void RoamMesh::applySample(RoamVertex& v, const HeightSample& s, bool morph) {
  if (morph && shown_) {
    v.fromHeightM = v.drawnHeight(timeS_, options_.fadeS);
    v.morphStartS = timeS_;
  }
  v.heightM = s.heightM;
  if (!v.merging) v.toHeightM = s.heightM;
  v.sourceZoom = s.sourceZoom;
  v.at = v.position(v.geometryHeight(options_.fillHeightM));
  // The ground normal: slopes in the vertex's own east/north/up, turned into the frame's axes.
  const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), v.up));
  const glm::dvec3 north = glm::cross(v.up, east);
  v.normal = glm::vec3(glm::normalize(v.up - east * s.slope.x - north * s.slope.y));
}

uint32_t RoamMesh::newVertex(GridPoint p, double fromHeight) {
  uint32_t i;
  if (!freeVertices_.empty()) {
    i = freeVertices_.back();
    freeVertices_.pop_back();
  } else {
    i = static_cast<uint32_t>(vertices_.size());
    vertices_.emplace_back();
  }
  RoamVertex& v = vertices_[i];
  v = RoamVertex{};
  v.grid = p;
  const glm::dvec2 lonLat = geo::tileXYToLonLat(grid_.tileXY(p, grid_.gridZoom()), grid_.gridZoom());
  const geo::Geodetic g{lonLat.y, lonLat.x, 0.0};
  v.base = frame_.toLocal(g);
  v.up = frame_.upAt(g, v.base);
  sampleVertex(v, false);
  if (shown_) {  // else: nothing drawn yet to morph from (markShown)
    v.fromHeightM = fromHeight;
    v.morphStartS = timeS_;
  }
  return i;
}

void RoamMesh::updateRadius(uint32_t t) {
  RoamNode& n = nodes_[t];
  const glm::dvec3 c = 0.5 * (vertices_[n.v[1]].at + vertices_[n.v[2]].at);
  n.radius = static_cast<float>(
      std::max(glm::length(vertices_[n.v[0]].at - c), glm::length(vertices_[n.v[1]].at - c)) * 1.0001 + 0.01);
}

float RoamMesh::thicknessOf(uint32_t t) {
  const RoamNode& n = nodes_[t];
  const float e = heights_->thickness(corners(t), n.path.level);
  if (!(e >= 0.0f)) return e;  // unknown (NaN) or no data (< 0)
  const glm::dvec3 hyp = vertices_[n.v[1]].base - vertices_[n.v[2]].base;
  return e + static_cast<float>(glm::dot(hyp, hyp) / (8.0 * kEarthRadiusM));
}

void RoamMesh::expire(uint32_t t) {
  constexpr double kNow = -std::numeric_limits<double>::infinity();
  nodes_[t].deadline = kNow;
  // A subtree's deadline is never later than its children's: stop at the first ancestor that
  // is already due.
  for (uint32_t u = t; u != kNoNode && nodes_[u].subtreeDeadline != kNow; u = nodes_[u].parent)
    nodes_[u].subtreeDeadline = kNow;
}

void RoamMesh::markDrawnChanged(uint32_t t) {
  // A chunk may start at any ancestor. A node stamped in this epoch has its ancestors stamped
  // already (every walk goes to the root or to such a node): stop there, so a resample that
  // marks thousands of nodes costs about one walk each.
  for (uint32_t u = t; u != kNoNode && nodes_[u].drawnStamp != drawnEpoch_; u = nodes_[u].parent)
    nodes_[u].drawnStamp = drawnEpoch_;
}

void RoamMesh::addLeaves(uint32_t t, int delta) {
  for (uint32_t u = t; u != kNoNode; u = nodes_[u].parent) {
    assert(delta > 0 || nodes_[u].leafCount > 1);
    nodes_[u].leafCount = static_cast<uint32_t>(static_cast<int64_t>(nodes_[u].leafCount) + delta);
  }
}

void RoamMesh::replaceLink(uint32_t at, uint32_t from, uint32_t to) {
  if (at == kNoNode) return;
  RoamNode& n = nodes_[at];
  if (n.base == from)
    n.base = to;
  else if (n.left == from)
    n.left = to;
  else if (n.right == from)
    n.right = to;
  else
    assert(false && "neighbour links are not symmetric");
}

void RoamMesh::splitOne(uint32_t t, uint32_t mid, std::vector<uint32_t>* created) {
  const uint32_t c = allocPair();  // may reallocate: index from here on
  RoamNode& n = nodes_[t];
  RoamNode& c0 = nodes_[c];
  RoamNode& c1 = nodes_[c + 1];
  c0.path = childPath(n.path, 0);
  c1.path = childPath(n.path, 1);
  c0.v[0] = mid;
  c0.v[1] = n.v[0];
  c0.v[2] = n.v[1];
  c1.v[0] = mid;
  c1.v[1] = n.v[2];
  c1.v[2] = n.v[0];
  c0.parent = c1.parent = t;
  c0.base = n.left;
  c1.base = n.right;
  c0.left = c + 1;
  c1.right = c;
  replaceLink(n.left, t, c);
  replaceLink(n.right, t, c + 1);
  n.child = c;
  n.mid = mid;
  ++leaves_;
  addLeaves(t, 1);  // one leaf became two
  expire(t);        // now a diamond half; its parent is no longer one
  if (n.parent != kNoNode) expire(n.parent);
  markDrawnChanged(t);
  nodes_[c].thickness = thicknessOf(c);
  nodes_[c + 1].thickness = thicknessOf(c + 1);
  updateRadius(c);
  updateRadius(c + 1);
  if (created) {
    created->push_back(c);
    created->push_back(c + 1);
  }
}

bool RoamMesh::split(uint32_t t, std::vector<uint32_t>* created) {
  if (!nodes_[t].isLeaf()) return true;
  if (nodes_[t].path.level >= grid_.maxLevel()) return false;
  // Forced split: the base neighbour must share our base before the diamond can split.
  if (nodes_[t].base != kNoNode && nodes_[nodes_[t].base].base != t) {
    if (!split(nodes_[t].base, created)) return false;
    assert(nodes_[nodes_[t].base].base == t);
  }
  const uint32_t b = nodes_[t].base;
  const RoamVertex& l = vertices_[nodes_[t].v[1]];
  const RoamVertex& r = vertices_[nodes_[t].v[2]];
  // Starts where the mesh was: on the base it splits (morphs to its sampled height from there).
  const double from = 0.5 * (l.drawnHeight(timeS_, options_.fadeS) + r.drawnHeight(timeS_, options_.fadeS));
  const uint32_t m = newVertex(midpoint(l.grid, r.grid), from);
  splitOne(t, m, created);
  raiseThickness(t);
  if (b != kNoNode) {
    splitOne(b, m, created);
    raiseThickness(b);
    const uint32_t tc = nodes_[t].child, bc = nodes_[b].child;
    nodes_[tc].right = bc + 1;
    nodes_[bc + 1].left = tc;
    nodes_[tc + 1].left = bc;
    nodes_[bc].right = tc + 1;
  }
  return true;
}

float RoamMesh::nestedThickness(uint32_t t) const {
  // Duchaineau's nested wedgie over the live mesh: the children's thickness plus how far the
  // split vertex is from the parent's base, so every descendant's wedgie lies inside.
  const RoamNode& n = nodes_[t];
  const float own = n.thickness;
  if (n.isLeaf()) return own;
  const float c0 = nodes_[n.child].thickness, c1 = nodes_[n.child + 1].thickness;
  if (!(c0 >= 0.0f) && !(c1 >= 0.0f)) return own;
  const double fill = options_.fillHeightM;
  const double dev = std::abs(vertices_[n.mid].geometryHeight(fill) -
                              0.5 * (vertices_[n.v[1]].geometryHeight(fill) + vertices_[n.v[2]].geometryHeight(fill)));
  const float nested = static_cast<float>(dev) + std::max({c0, c1, 0.0f});
  return own >= 0.0f ? std::max(own, nested) : nested;
}

void RoamMesh::raiseThickness(uint32_t t) {
  // Splits only add what was unknown before: walk up while a parent's bound grows.
  for (; t != kNoNode; t = nodes_[t].parent) {
    const float e = nestedThickness(t);
    if (!(e > nodes_[t].thickness) && nodes_[t].thickness == nodes_[t].thickness) break;
    nodes_[t].thickness = e;
    expire(t);
  }
}

bool RoamMesh::isMergeable(uint32_t t) const {
  auto childrenAreLeaves = [&](uint32_t n) {
    const RoamNode& x = nodes_[n];
    return !x.isLeaf() && nodes_[x.child].isLeaf() && nodes_[x.child + 1].isLeaf();
  };
  if (!childrenAreLeaves(t)) return false;
  const uint32_t b = nodes_[t].base;
  return b == kNoNode || (nodes_[b].base == t && childrenAreLeaves(b));
}

void RoamMesh::beginMergeMorph(uint32_t t) {
  RoamVertex& m = vertices_[nodes_[t].mid];
  if (m.merging) return;
  const RoamVertex& l = vertices_[nodes_[t].v[1]];
  const RoamVertex& r = vertices_[nodes_[t].v[2]];
  m.fromHeightM = m.drawnHeight(timeS_, options_.fadeS);
  m.toHeightM = 0.5 * (l.drawnHeight(timeS_, options_.fadeS) + r.drawnHeight(timeS_, options_.fadeS));
  m.morphStartS = timeS_;
  m.merging = true;
  markDiamondLeaves(t);
}

void RoamMesh::cancelMergeMorph(uint32_t t) {
  RoamVertex& m = vertices_[nodes_[t].mid];
  if (!m.merging) return;
  m.fromHeightM = m.drawnHeight(timeS_, options_.fadeS);
  m.toHeightM = m.heightM;
  m.morphStartS = timeS_;
  m.merging = false;
  markDiamondLeaves(t);
}

void RoamMesh::markDiamondLeaves(uint32_t t) {
  // The leaves that share the diamond's split vertex: the children of t and of its base.
  for (uint32_t half : {t, nodes_[t].base}) {
    if (half == kNoNode || nodes_[half].isLeaf()) continue;
    markDrawnChanged(nodes_[half].child);
    markDrawnChanged(nodes_[half].child + 1);
  }
}

void RoamMesh::mergeOne(uint32_t t) {
  RoamNode& n = nodes_[t];
  const uint32_t c = n.child;
  n.left = nodes_[c].base;
  n.right = nodes_[c + 1].base;
  replaceLink(n.left, c, t);
  replaceLink(n.right, c + 1, t);
  freePair(c);
  n.child = kNoNode;
  n.mid = kNoNode;
  --leaves_;
  addLeaves(t, -1);
  expire(t);  // a leaf again; its parent may have become a diamond half
  if (n.parent != kNoNode) expire(n.parent);
  markDrawnChanged(t);
}

void RoamMesh::merge(uint32_t t) {
  assert(isMergeable(t));
  const uint32_t b = nodes_[t].base;
  const uint32_t m = nodes_[t].mid;
  mergeOne(t);
  if (b != kNoNode) mergeOne(b);
  freeVertices_.push_back(m);
}

}  // namespace vegstream::terrain
