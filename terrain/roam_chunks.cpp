// ROAM output's drawn chunks (roam_tessellator.h, "The output cache"): each chunk keeps the
// drawn leaves of one subtree between frames, built again only when something under it changed.
// The traversal (roam_output.cpp) claims the chunks it reaches; the work per chunk — building
// it, moving its morphing vertices, culling the triangles of one that straddles the edge of the
// view — then runs on options_.tasks, since each chunk touches only itself; the draws are
// appended in traversal order, so the output is the same with any number of threads.
// Seed 001_3eca9f2c7752e4fb.txt §3.1 (the drawn triangulation, eye-space culling).

#include <algorithm>
#include <bit>
#include <cassert>

#include "core/parallel_for.h"
#include "terrain/roam_tessellator.h"
#include "terrain/roam_walk.h"

namespace vegstream::terrain {

void RoamTessellator::drawChunk(Walk& w, uint32_t t, int piece, PlaneMask planes) {
  const geo::TileId& tile = w.pieces->tiles()[size_t(piece)];
  uint32_t slot = mesh_.node(t).drawnChunk;
  if (slot == kNoNode) {
    if (freeChunks_.empty()) {
      slot = static_cast<uint32_t>(chunks_.size());
      chunks_.emplace_back();
    } else {
      slot = freeChunks_.back();
      freeChunks_.pop_back();
    }
    // While a compaction's copy reads the nodes the attachment waits: finishCompaction attaches
    // every chunk to its root again (chunks_[slot].root, set below).
    if (!compaction_) mesh_.node(t).drawnChunk = slot;
    chunks_[slot].root = kNoNode;
  }
  DrawnChunk& chunk = chunks_[slot];
  chunk.usedFrame = outputFrame_;
  chunk.rebuild = chunk.root != t || mesh_.node(t).drawnStamp > chunk.builtStamp || !(chunk.piece == tile);
  if (chunk.rebuild) {
    chunk.root = t;
    chunk.piece = tile;
    chunk.builtStamp = chunkEpoch_;
    chunk.mesh.id = nextChunkId_++;
    chunk.mesh.version = 0;
    ++figures_.chunksBuilt;
  } else {
    ++figures_.chunksReused;
  }
  w.chunkDraws.push_back({slot, piece, planes});
  if (options_.tasks) return;  // prepared on the workers, appended in order (prepareChunks)
  // One thread: prepared and appended at once, while the chunk is still in the cache.
  if (chunkScratch_.empty()) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}, {}});
  prepareChunk(w, w.chunkDraws.size() - 1, chunkScratch_[0], w.emitted);
  appendChunkDraw(w, w.chunkDraws.back());
  w.chunkDraws.clear();
}

void RoamTessellator::prepareChunks(Walk& w) {
  // Blocks of chunks, each with its own scratch: a task per chunk would cost more than most
  // chunks (a reused one with nothing morphing and wholly in view is nothing to do).
  constexpr size_t kBlock = 16;
  const size_t n = w.chunkDraws.size();
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<EmitCounts> counts(blocks);
  // Each block's scratch, kept from output to output (a map is a few kB to clear otherwise).
  while (chunkScratch_.size() < blocks) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}, {}});
  const auto block = [&](size_t b) -> Status {
    ChunkScratch& scratch = chunkScratch_[b];
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
      prepareChunk(w, i, scratch, counts[b]);
    return {};
  };
  if (options_.tasks && blocks > 1) {
    const Status done = parallelFor(blocks, 0, options_.tasks, block);
    assert(done.ok());
    (void)done;
  } else {
    for (size_t b = 0; b < blocks; ++b) (void)block(b);
  }
  for (const EmitCounts& c : counts) w.emitted.add(c);
}

void RoamTessellator::prepareChunk(const Walk& w, size_t draw, ChunkScratch& scratch, EmitCounts& counts) {
  // Any thread: reads the mesh, writes this chunk (and the caller's scratch and counts) only.
  const ChunkDraw& d = w.chunkDraws[draw];
  DrawnChunk& chunk = chunks_[d.slot];
  const glm::dvec3& origin = (*w.meshes)[size_t(d.piece)].origin;
  if (chunk.rebuild) {
    chunk.mesh.vertices.clear();
    chunk.mesh.indices.clear();
    chunk.morphing.clear();
    chunk.thickness.clear();
    chunk.at.clear();
    scratch.map.clear();
    const LeafSink sink{&chunk.mesh.vertices, &chunk.mesh.indices, origin, &chunk.piece, 0, &scratch.map, &counts, &chunk};
    collectChunk(chunk.root, scratch.leaves);
    for (const uint32_t leaf : scratch.leaves) emitLeaf(w.timeS, leaf, sink);
  } else if (!chunk.morphing.empty()) {
    // Unchanged but for its morphing vertices: move them to where they are drawn now.
    const double fade = mesh_.options().fadeS;
    size_t kept = 0;
    ++chunk.mesh.version;
    ++counts.chunksMoved;
    for (size_t i = 0; i < chunk.morphing.size(); ++i) {
      const DrawnChunk::Morphing& m = chunk.morphing[i];
      const double h = m.drawnHeight(w.timeS, fade);
      TerrainVertex& out = chunk.mesh.vertices[m.at];
      out.position = glm::vec3(m.position(h) - origin);
      out.heightMsl = static_cast<float>(h);
      if (h != m.heightM) ++counts.morphingVertices;
      if (m.morphDone(w.timeS, fade)) continue;
      if (kept != i) chunk.morphing[kept] = m;
      ++kept;
    }
    chunk.morphing.erase(chunk.morphing.begin() + static_cast<std::ptrdiff_t>(kept), chunk.morphing.end());
  }
  chunk.visible.clear();
  if (d.planes == 0 || chunk.mesh.indices.empty()) return;
  // Straddling the edge of the view: each triangle's wedgie (grown by the canopy) culled on its
  // own, from its vertices' plane distances (each vertex transformed once); the vertices of
  // culled triangles stay in the chunk, unreferenced.
  // Only the planes the root's wedgie straddles can cull a triangle (each triangle's wedgie lies
  // inside the root's, eye_space.h), and of those only the ones some vertex is outside: a plane
  // every vertex is inside culls none of them (a prism reaches at least as far in as its
  // triangle: below, above ≥ 0). Most such chunks straddle one plane of the five.
  std::vector<PlaneDistances>& planes = scratch.planes;
  planes.resize(chunk.at.size());
  double lowest[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (size_t i = 0; i < chunk.at.size(); ++i) {
    const glm::dvec3 q = w.view->toEye(chunk.at[i]);
    for (PlaneMask m = d.planes; m != 0; m = static_cast<PlaneMask>(m & (m - 1))) {
      const int k = std::countr_zero(m);
      planes[i].d[k] = w.frustum->distance(q, k);
      lowest[k] = std::min(lowest[k], planes[i].d[k]);
    }
  }
  int straddled[5], count = 0;
  for (int k = 0; k < 5; ++k)
    if (lowest[k] < 0.0) straddled[count++] = k;
  const std::vector<uint32_t>& indices = chunk.mesh.indices;
  for (size_t t = 0; t < chunk.thickness.size(); ++t) {
    const uint32_t* tri = &indices[3 * t];
    const double e = chunk.thickness[t];
    bool outside = false;
    for (int j = 0; j < count && !outside; ++j)
      outside = wedgieOutsidePlane(*w.frustum, planes[tri[0]], planes[tri[1]], planes[tri[2]], e, e + options_.canopyM,
                                   straddled[j]);
    if (!outside) chunk.visible.insert(chunk.visible.end(), tri, tri + 3);
  }
}

void RoamTessellator::appendChunkDraws(Walk& w) {
  for (const ChunkDraw& d : w.chunkDraws) appendChunkDraw(w, d);
}

void RoamTessellator::appendChunkDraw(Walk& w, const ChunkDraw& d) {
  const DrawnChunk& chunk = chunks_[d.slot];
  TerrainMesh& m = (*w.meshes)[size_t(d.piece)];
  const std::vector<uint32_t>& indices = chunk.mesh.indices;
  if (indices.empty()) return;  // no data under it
  if (d.planes == 0) {
    m.chunks.push_back({&chunk.mesh, false, 0, static_cast<uint32_t>(indices.size())});
    figures_.drawnTriangles += indices.size() / 3;
    return;
  }
  const auto first = static_cast<uint32_t>(m.chunkIndices.size());
  const auto count = static_cast<uint32_t>(chunk.visible.size());
  m.chunkIndices.insert(m.chunkIndices.end(), chunk.visible.begin(), chunk.visible.end());
  if (count > 0) m.chunks.push_back({&chunk.mesh, true, first, count});
  figures_.drawnTriangles += count / 3;
}

void RoamTessellator::collectChunk(uint32_t root, std::vector<uint32_t>& leaves) const {
  // The subtree's leaves, depth first (the order the direct output emits them in). Emitting a
  // leaf reads its three vertices, scattered over the pool: asking for all of them here, before
  // the first is needed, overlaps the misses that reading them one by one waited for in turn.
  leaves.clear();
  uint32_t stack[128];
  int depth = 0;
  stack[depth++] = root;
  while (depth > 0) {
    const uint32_t t = stack[--depth];
    const RoamNode& n = mesh_.node(t);
    if (n.isLeaf()) {
      leaves.push_back(t);
      continue;
    }
    mesh_.prefetchChildren(t);
    assert(depth + 2 <= 128 && "a chunk's subtree is shallower than 127 levels");
    stack[depth++] = n.child + 1;
    stack[depth++] = n.child;
  }
  for (const uint32_t leaf : leaves)
    for (const uint32_t v : mesh_.node(leaf).v) mesh_.prefetchVertex(v);
}

void RoamTessellator::dropIdleChunks() {
  for (uint32_t slot = 0; slot < chunks_.size(); ++slot) {
    DrawnChunk& c = chunks_[slot];
    if (c.root == kNoNode || c.usedFrame + kChunkIdleFrames > outputFrame_) continue;
    mesh_.node(c.root).drawnChunk = kNoNode;
    c = DrawnChunk{};  // its memory goes: an idle chunk is not coming back soon
    freeChunks_.push_back(slot);
  }
}

void RoamTessellator::releaseChunks() {
  for (uint32_t slot : mesh_.takeReleasedChunks()) {
    chunks_[slot] = DrawnChunk{};
    freeChunks_.push_back(slot);
  }
}

void RoamTessellator::remapChunks(const RoamRenumbering& renumbering) {
  // Chunks whose root was freed are released before compaction: every index here is live.
  auto node = [&](uint32_t i) { return i == kNoNode ? kNoNode : renumbering.nodes[i]; };
  // The compacted nodes hold no chunk (RoamMesh::compact): each is attached to its root again.
  for (uint32_t slot = 0; slot < chunks_.size(); ++slot) {
    DrawnChunk& c = chunks_[slot];
    if (c.root == kNoNode) continue;
    c.root = node(c.root);
    mesh_.node(c.root).drawnChunk = slot;
  }
}

}  // namespace vegstream::terrain
