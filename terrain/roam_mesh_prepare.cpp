// RoamMesh::prepareSplits (roam_mesh.h): what the split queue's splits will compute from the
// ground alone, computed ahead in parallel. Seed 001_3eca9f2c7752e4fb.txt §3.1 (ROAM's split:
// the new vertex sampled from the heightmap, the children's nested wedgies).
//
// Why: the split queue has to stay on one thread (each split changes what the next one sees),
// and while the mesh grows fast — a descent brings 250–400 splits a frame — most of a split's
// time went into sampling its new vertex (bilinear heights and slopes, the geodetic position)
// and its children's tile thicknesses (wedgie tables, deeper levels computed from the pixels).
// Those depend only on the grid point or the triangle and on the resident tiles, which nothing
// changes during the queue: they are computed here for every leaf the queue holds, on the
// workers, and split() looks them up. A leaf split by force (a coarser neighbour's), or one
// whose lookups needed a tile the frame had not cached yet, is computed in split() as before.

#include <algorithm>
#include <array>
#include <cassert>

#include "core/parallel_for.h"
#include "terrain/roam_mesh.h"

namespace vegstream::terrain {

const RoamMesh::PreparedSplit* RoamMesh::findPrepared(GridPoint mid) const {
  if (prepared_.empty()) return nullptr;
  const uint64_t key = packGridPoint(mid);
  const auto it = std::lower_bound(prepared_.begin(), prepared_.end(), key,
                                   [](const PreparedSplit& s, uint64_t k) { return s.key < k; });
  return it != prepared_.end() && it->key == key ? &*it : nullptr;
}

bool RoamMesh::preparedThickness(const TriCorners& c, int level, float* thickness) const {
  // A split's children have its split vertex as their apex.
  const PreparedSplit* s = findPrepared(c.apex);
  if (!s || s->level != level) return false;
  for (int k = 0; k < s->childCount; ++k) {
    const PreparedSplit::Child& child = s->children[size_t(k)];
    if (child.ok && child.corners.left == c.left && child.corners.right == c.right) {
      *thickness = child.thickness;
      return true;
    }
  }
  return false;
}

void RoamMesh::prepareSplits(std::span<const uint32_t> leaves, TaskRunner* tasks) {
  dropPrepared();
  if (leaves.empty()) return;
  // On this thread: what each split will make, and the tiles its lookups start from cached, so
  // that the workers' copies of the heights find them (ResidentHeights::cachedOnly).
  std::vector<PreparedSplit>& splits = prepared_;
  splits.reserve(leaves.size());
  for (const uint32_t t : leaves) {
    const RoamNode& n = nodes_[t];
    if (!n.isLeaf() || n.path.level >= grid_.maxLevel()) continue;
    const uint32_t b = n.base;
    // A coarser base neighbour is split first (forced): its own split vertex comes first, and
    // t's partner is then one of its children. Only a diamond's split is known ahead.
    if (b != kNoNode && nodes_[b].base != t) continue;
    PreparedSplit& s = splits.emplace_back();
    const TriCorners c = corners(t);
    s.mid = midpoint(c.left, c.right);
    s.key = packGridPoint(s.mid);
    s.level = n.path.level + 1;
    heights_->cacheFor(s.mid);
    for (const uint32_t half : {t, b}) {
      if (half == kNoNode) continue;
      const TriCorners h = corners(half);
      for (int which = 0; which < 2; ++which) {
        PreparedSplit::Child& child = s.children[size_t(s.childCount++)];
        child.corners = terrain::child(h, which);
        heights_->cacheFor(child.corners, s.level);
      }
    }
  }
  // On the workers, through views of the heights that read the tiles cached above.
  const size_t n = splits.size();
  constexpr size_t kBlock = 16;
  const Status done = parallelFor((n + kBlock - 1) / kBlock, 0, tasks, [&](size_t block) -> Status {
    bool missed = false;
    ResidentHeights view = heights_->cachedOnly(&missed);
    for (size_t i = block * kBlock; i < std::min(n, (block + 1) * kBlock); ++i) {
      PreparedSplit& s = splits[i];
      missed = false;
      s.vertex = makeVertex(s.mid, view);
      s.vertexOk = !missed;
      for (int k = 0; k < s.childCount; ++k) {
        PreparedSplit::Child& child = s.children[size_t(k)];
        missed = false;
        child.thickness = view.thickness(child.corners, s.level);
        child.ok = !missed;
      }
    }
    return {};
  });
  assert(done.ok());
  (void)done;
  // Two leaves of one diamond (both queued) give the same split twice: either serves.
  std::sort(splits.begin(), splits.end(), [](const PreparedSplit& a, const PreparedSplit& b) { return a.key < b.key; });
}

void RoamMesh::dropPrepared() { prepared_.clear(); }

}  // namespace vegstream::terrain
