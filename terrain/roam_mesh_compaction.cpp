// RoamMesh's compaction (roam_mesh.h): the pools renumbered in depth-first order, so that the
// traversals (Duchaineau et al. 1997; seed 001_3eca9f2c7752e4fb.txt §3.1) walk memory forwards.
// A compaction reads every node and vertex in tree order: 5–10 ms at 80 k leaves on one thread,
// the slowest frames of a flight (issue 17). So where each node and vertex goes is worked out
// without a copy in between, and subtrees are copied in parallel:
//
//   - The roots keep their indices. The children of split node t are the pair at R + 2·k(t)
//     (R roots), k(t) being t's rank among the split nodes in preorder, roots in order: the
//     order one depth-first copy appends them in. A subtree of L leaves holds L − 1 split nodes,
//     so the ranks after a subtree follow from its leafCount without visiting it.
//   - A diamond's split vertex belongs to its half of lower rank (the half such a copy meets
//     first), numbered in that order after the root corners: each subtree counts the vertices it
//     owns, and a prefix sum over the subtrees in order gives each the first of its indices.
//
// Phases over items — the top of the forest, walked here, and the subtrees of at most
// kCopyLeaves leaves below it, handed out whole — in parallel on `tasks`: (1) a walk of each item
// ranks its split nodes, copies every node to its new index while it is in the cache, and notes
// each split node's vertex and base neighbour by rank; (2) the vertices each item owns are
// counted (comparing ranks with neighbours in other items, so after every rank is known); (3)
// they are copied; (4) the links are renumbered over the copy. Without `tasks` one walk of the
// whole forest does (1) to (3), numbering each vertex where it first meets it: the same pools,
// without the ranks' two extra passes (BM_RoamCompaction: 88 k leaves, one thread 5.1 ms, as
// before this file; two 4.0 ms, on a 2-vCPU machine).

#include <algorithm>
#include <cassert>

#include "core/parallel_for.h"
#include "terrain/roam_mesh.h"

namespace vegstream::terrain {
namespace {

constexpr uint32_t kCopyLeaves = 2048;  // the largest subtree one item copies

// An item: a node of the top alone, or a whole subtree. Its split nodes are the ranks
// [rank, rank + splits), in preorder.
struct CopyItem {
  uint32_t node = kNoNode;
  bool whole = false;
  uint32_t rank = 0;
  uint32_t splits = 0;
  uint32_t owned = 0;  // split vertices the item owns
  uint32_t firstVertex = 0;
};

template <class Work>
void forEachItem(size_t n, TaskRunner* tasks, const Work& work) {
  if (!tasks) {
    for (size_t i = 0; i < n; ++i) work(i);
    return;
  }
  const Status done = parallelFor(n, 0, tasks, [&](size_t i) {
    work(i);
    return Status{};
  });
  assert(done.ok());
  (void)done;
}

// One buildCompaction: reads the mesh's pools, writes the copy and the renumbering into c.
class CompactionBuilder {
 public:
  CompactionBuilder(const std::vector<RoamNode>& nodes, const std::vector<RoamVertex>& vertices,
                    const std::vector<uint32_t>& roots, const std::vector<uint32_t>& corners, uint64_t leaves,
                    RoamCompaction& c, TaskRunner* tasks)
      : nodes_(nodes), vertices_(vertices), roots_(roots), corners_(corners), c_(c), tasks_(tasks),
        nodeMap_(c.renumbering.nodes), vertexMap_(c.renumbering.vertices),
        rootCount_(static_cast<uint32_t>(roots.size())),
        splitCount_(static_cast<uint32_t>(leaves - rootCount_)),  // L − 1 per root
        serial_(tasks == nullptr) {}

  void build() {
    start();
    std::vector<CopyItem> items = walkTop();
    if (!serial_) numberVertices(items);
    renumberLinks();
  }

 private:
  // The maps and the copy sized. One thread walks the whole forest in preorder and gives each
  // split vertex the next index where its diamond's first half meets it; in parallel, the ranks
  // decide (phases 2 and 3).
  void start() {
    nodeMap_.assign(nodes_.size(), kNoNode);
    vertexMap_.assign(vertices_.size(), kNoNode);
    if (serial_) {
      c_.vertices.clear();
      for (uint32_t v : corners_) {
        vertexMap_[v] = static_cast<uint32_t>(c_.vertices.size());
        c_.vertices.push_back(vertices_[v]);
      }
    } else {
      c_.ranks.resize(nodes_.size());  // by old index, split nodes only
      c_.splits.resize(splitCount_);   // by rank
    }
    c_.nodes.resize(size_t(rootCount_) + 2 * size_t(splitCount_));  // constructs beyond the old size only
  }

  // Node t, its new index known, gets its rank k (when split): its copy, its children's indices.
  void place(uint32_t t, uint32_t k) {
    const RoamNode& n = nodes_[t];
    RoamNode& copy = c_.nodes[nodeMap_[t]];
    copy = n;
    copy.drawnChunk = kNoNode;  // the tessellator attaches its chunks again
    if (n.isLeaf()) return;
    nodeMap_[n.child] = rootCount_ + 2 * k;
    nodeMap_[n.child + 1] = rootCount_ + 2 * k + 1;
    if (!serial_) {
      c_.ranks[t] = k;
      c_.splits[k] = {n.mid, n.base};
    } else if (vertexMap_[n.mid] == kNoNode) {
      vertexMap_[n.mid] = static_cast<uint32_t>(c_.vertices.size());
      c_.vertices.push_back(vertices_[n.mid]);
    }
  }

  // A whole subtree placed, in preorder.
  void walk(const CopyItem& item) {
    uint32_t k = item.rank;
    std::vector<uint32_t> below{item.node};
    while (!below.empty()) {
      const uint32_t t = below.back();
      below.pop_back();
      place(t, k);
      const RoamNode& n = nodes_[t];
      if (n.isLeaf()) continue;
      ++k;
      below.push_back(n.child + 1);
      below.push_back(n.child);
    }
    assert(k == item.rank + item.splits);
  }

  // The top, in preorder: its nodes placed here, the subtrees below it made items (walked at
  // once by one thread).
  std::vector<CopyItem> walkTop() {
    std::vector<CopyItem> items;
    uint32_t next = 0;  // the next split node's rank
    std::vector<uint32_t> stack(roots_.rbegin(), roots_.rend());
    for (uint32_t r : roots_) nodeMap_[r] = r;  // roots are the first pairs, in order
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      const RoamNode& n = nodes_[t];
      if (n.isLeaf() || n.leafCount > kCopyLeaves) {
        const uint32_t splits = n.isLeaf() ? 0 : 1;
        items.push_back({t, false, next, splits});
        place(t, next);
        next += splits;
        if (n.isLeaf()) continue;
        stack.push_back(n.child + 1);
        stack.push_back(n.child);
      } else {
        const CopyItem item{t, true, next, n.leafCount - 1};  // a subtree of L leaves holds L − 1 split nodes
        if (serial_)
          walk(item);
        else
          items.push_back(item);
        next += n.leafCount - 1;
      }
    }
    assert(next == splitCount_);
    return items;
  }

  // A split node owns its split vertex when it comes before the other half of its diamond
  // (whose base neighbour, if any, is split too: splits split diamonds).
  bool owns(uint32_t k) const {
    const uint32_t base = c_.splits[k].base;
    assert(base == kNoNode || !nodes_[base].isLeaf());
    return base == kNoNode || k < c_.ranks[base];
  }

  // Phases (1) to (3), in parallel.
  void numberVertices(std::vector<CopyItem>& items) {
    // (1) Each subtree walked: ranks, copies, and its split nodes' vertices and bases by rank.
    forEachItem(items.size(), tasks_, [&](size_t i) {
      if (items[i].whole) walk(items[i]);
    });
    // (2) The vertices each item owns.
    forEachItem(items.size(), tasks_, [&](size_t i) {
      uint32_t owned = 0;
      for (uint32_t k = items[i].rank; k < items[i].rank + items[i].splits; ++k) owned += owns(k) ? 1u : 0u;
      items[i].owned = owned;
    });
    auto vertexCount = static_cast<uint32_t>(corners_.size());
    for (CopyItem& item : items) {
      item.firstVertex = vertexCount;
      vertexCount += item.owned;
    }
    // (3) The vertices: the root corners first, then each item's in rank order.
    c_.vertices.resize(vertexCount);
    for (uint32_t v = 0; v < corners_.size(); ++v) {
      vertexMap_[corners_[v]] = v;
      c_.vertices[v] = vertices_[corners_[v]];
    }
    forEachItem(items.size(), tasks_, [&](size_t i) {
      uint32_t v = items[i].firstVertex;
      for (uint32_t k = items[i].rank; k < items[i].rank + items[i].splits; ++k) {
        if (!owns(k)) continue;
        vertexMap_[c_.splits[k].mid] = v;
        c_.vertices[v++] = vertices_[c_.splits[k].mid];
      }
      assert(v == items[i].firstVertex + items[i].owned);
    });
  }

  // (4) Links renumbered, over the copy in blocks (it is in memory order now).
  void renumberLinks() {
    constexpr size_t kBlock = 8192;
    auto mapNode = [&](uint32_t i) { return i == kNoNode ? kNoNode : nodeMap_[i]; };
    forEachItem((c_.nodes.size() + kBlock - 1) / kBlock, tasks_, [&](size_t b) {
      const size_t end = std::min(c_.nodes.size(), (b + 1) * kBlock);
      for (size_t i = b * kBlock; i < end; ++i) {
        RoamNode& n = c_.nodes[i];
        n.parent = mapNode(n.parent);
        n.child = mapNode(n.child);
        n.base = mapNode(n.base);
        n.left = mapNode(n.left);
        n.right = mapNode(n.right);
        if (n.mid != kNoNode) n.mid = vertexMap_[n.mid];
        for (uint32_t& v : n.v) v = vertexMap_[v];
      }
    });
  }

  const std::vector<RoamNode>& nodes_;
  const std::vector<RoamVertex>& vertices_;
  const std::vector<uint32_t>& roots_;
  const std::vector<uint32_t>& corners_;
  RoamCompaction& c_;
  TaskRunner* tasks_;
  std::vector<uint32_t>& nodeMap_;
  std::vector<uint32_t>& vertexMap_;
  const uint32_t rootCount_;
  const uint32_t splitCount_;
  const bool serial_;
};

}  // namespace

RoamCompaction RoamMesh::beginCompaction() {
  RoamCompaction c;
  c.nodes = std::move(spareNodes_);  // kept from the last compaction: no pages faulted in again
  c.vertices = std::move(spareVertices_);
  c.nodes.reserve(nodes_.capacity());  // the pools swap: both keep what reserve() asked for
  c.vertices.reserve(vertices_.capacity());
  return c;
}

void RoamMesh::buildCompaction(RoamCompaction& c, TaskRunner* tasks) const {
  CompactionBuilder(nodes_, vertices_, roots_, cornerVertices_, leaves_, c, tasks).build();
}

RoamRenumbering RoamMesh::endCompaction(RoamCompaction&& c) {
  for (uint32_t& v : cornerVertices_) v = c.renumbering.vertices[v];
  nodes_.swap(c.nodes);
  vertices_.swap(c.vertices);
  spareNodes_ = std::move(c.nodes);  // the old pools: the next compaction's scratch
  spareVertices_ = std::move(c.vertices);
  freePairs_.clear();
  freeVertices_.clear();
  pairsAllocated_ = 0;
  return std::move(c.renumbering);
}

}  // namespace vegstream::terrain
