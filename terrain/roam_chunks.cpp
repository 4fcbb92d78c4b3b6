// DrawnChunks (roam_chunks.h): ROAM output's drawn chunks. Each chunk keeps the drawn leaves of
// one subtree between frames, built again only when something under it changed. The traversal
// (roam_output.cpp) claims the chunks it reaches; the work per chunk — building it, moving its
// morphing vertices, culling the triangles of one that straddles the edge of the view — then
// runs on options_.tasks, since each chunk touches only itself; the draws are appended in
// traversal order, so the output is the same with any number of threads.
// Seed 001_3eca9f2c7752e4fb.txt §3.1 (the drawn triangulation, eye-space culling).

#include "terrain/roam_chunks.h"

#include <algorithm>
#include <bit>
#include <cassert>

#include "core/parallel_for.h"

namespace vegstream::terrain {

DrawnChunks::DrawnChunks(RoamMesh& mesh, const RoamOptions& options, RoamFigures& figures)
    : mesh_(mesh), options_(options), figures_(figures) {}

void DrawnChunks::beginOutput() {
  ++outputFrame_;
  release();
  // Changes from here on are after every chunk this output builds.
  chunkEpoch_ = mesh_.closeDrawnEpoch();
}

uint32_t DrawnChunks::slotFor(uint32_t t, bool attach) {
  uint32_t slot = mesh_.node(t).drawnChunk;
  if (slot != kNoNode) return slot;
  if (freeChunks_.empty()) {
    slot = static_cast<uint32_t>(chunks_.size());
    chunks_.emplace_back();
  } else {
    slot = freeChunks_.back();
    freeChunks_.pop_back();
  }
  // While a compaction's copy reads the nodes the attachment waits: the end of the compaction
  // attaches every chunk to its root again (remap: chunks_[slot].root, set below).
  if (attach) mesh_.node(t).drawnChunk = slot;
  chunks_[slot].root = kNoNode;
  return slot;
}

void DrawnChunks::draw(const ChunkPass& pass, uint32_t t, int piece, PlaneMask planes) {
  const geo::TileId& tile = pass.pieces->tiles()[size_t(piece)];
  const uint32_t slot = slotFor(t, pass.attach);
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
  draws_.push_back({slot, piece, planes});
  if (options_.tasks) return;  // prepared on the workers, appended in order (finish)
  // One thread: prepared and appended at once, while the chunk is still in the cache.
  if (chunkScratch_.empty()) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}, {}});
  prepare(pass, draws_.size() - 1, chunkScratch_[0], *pass.emitted);
  append(pass, draws_.back());
  draws_.clear();
}

void DrawnChunks::finish(const ChunkPass& pass) {
  prepareAll(pass);
  for (const ChunkDraw& d : draws_) append(pass, d);
  draws_.clear();
}

void DrawnChunks::prepareAll(const ChunkPass& pass) {
  // Blocks of chunks, each with its own scratch: a task per chunk would cost more than most
  // chunks (a reused one with nothing morphing and wholly in view is nothing to do).
  constexpr size_t kBlock = 16;
  const size_t n = draws_.size();
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<EmitCounts> counts(blocks);
  // Each block's scratch, kept from output to output (a map is a few kB to clear otherwise).
  while (chunkScratch_.size() < blocks) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}, {}});
  const auto block = [&](size_t b) -> Status {
    ChunkScratch& scratch = chunkScratch_[b];
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) prepare(pass, i, scratch, counts[b]);
    return {};
  };
  if (options_.tasks && blocks > 1) {
    const Status done = parallelFor(blocks, 0, options_.tasks, block);
    assert(done.ok());
    (void)done;
  } else {
    for (size_t b = 0; b < blocks; ++b) (void)block(b);
  }
  for (const EmitCounts& c : counts) pass.emitted->add(c);
}

void DrawnChunks::prepare(const ChunkPass& pass, size_t draw, ChunkScratch& scratch, EmitCounts& counts) {
  const ChunkDraw& d = draws_[draw];
  DrawnChunk& chunk = chunks_[d.slot];
  const glm::dvec3& origin = (*pass.meshes)[size_t(d.piece)].origin;
  if (chunk.rebuild) {
    rebuild(pass, chunk, origin, scratch, counts);
    keepBounds(chunk.mesh);
  } else if (!chunk.morphing.empty()) {
    move(pass, chunk, origin, counts);
    keepBounds(chunk.mesh);
  }
  chunk.visible.clear();
  if (d.planes == 0 || chunk.mesh.indices.empty()) return;
  cullTriangles(pass, chunk, d.planes, scratch);
}

void DrawnChunks::rebuild(const ChunkPass& pass, DrawnChunk& chunk, const glm::dvec3& origin, ChunkScratch& scratch,
                          EmitCounts& counts) {
  chunk.mesh.vertices.clear();
  chunk.mesh.indices.clear();
  chunk.morphing.clear();
  chunk.thickness.clear();
  chunk.at.clear();
  scratch.map.clear();
  const LeafSink sink{.vertices = &chunk.mesh.vertices,
                      .indices = &chunk.mesh.indices,
                      .origin = origin,
                      .tile = &chunk.piece,
                      .stamps = nullptr,
                      .frame = 0,
                      .stamp = 0,
                      .chunkVertices = &scratch.map,
                      .counts = &counts,
                      .morphing = &chunk.morphing,
                      .at = &chunk.at,
                      .thickness = &chunk.thickness};
  collect(chunk.root, scratch.leaves);
  for (const uint32_t leaf : scratch.leaves) emitLeaf(mesh_, pass.timeS, leaf, sink);
}

void DrawnChunks::move(const ChunkPass& pass, DrawnChunk& chunk, const glm::dvec3& origin, EmitCounts& counts) {
  // Unchanged but for its morphing vertices: move them to where they are drawn now.
  const double fade = mesh_.options().fadeS;
  size_t kept = 0;
  ++chunk.mesh.version;
  ++counts.chunksMoved;
  for (size_t i = 0; i < chunk.morphing.size(); ++i) {
    const MorphingVertex& m = chunk.morphing[i];
    const double h = m.drawnHeight(pass.timeS, fade);
    TerrainVertex& out = chunk.mesh.vertices[m.at];
    out.position = glm::vec3(m.position(h) - origin);
    out.heightMsl = static_cast<float>(h);
    if (h != m.heightM) ++counts.morphingVertices;
    if (m.morphDone(pass.timeS, fade)) continue;
    if (kept != i) chunk.morphing[kept] = m;
    ++kept;
  }
  chunk.morphing.erase(chunk.morphing.begin() + static_cast<std::ptrdiff_t>(kept), chunk.morphing.end());
}

void DrawnChunks::cullTriangles(const ChunkPass& pass, DrawnChunk& chunk, PlaneMask rootPlanes, ChunkScratch& scratch) {
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
    const glm::dvec3 q = pass.view->toEye(chunk.at[i]);
    for (PlaneMask m = rootPlanes; m != 0; m = static_cast<PlaneMask>(m & (m - 1))) {
      const int k = std::countr_zero(m);
      planes[i].d[k] = pass.frustum->distance(q, k);
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
      outside = wedgieOutsidePlane(*pass.frustum, planes[tri[0]], planes[tri[1]], planes[tri[2]], e,
                                   e + options_.canopyM, straddled[j]);
    if (!outside) chunk.visible.insert(chunk.visible.end(), tri, tri + 3);
  }
}

void DrawnChunks::append(const ChunkPass& pass, const ChunkDraw& d) {
  const DrawnChunk& chunk = chunks_[d.slot];
  TerrainMesh& m = (*pass.meshes)[size_t(d.piece)];
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

void DrawnChunks::collect(uint32_t root, std::vector<uint32_t>& leaves) const {
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

void DrawnChunks::dropIdle() {
  for (uint32_t slot = 0; slot < chunks_.size(); ++slot) {
    DrawnChunk& c = chunks_[slot];
    if (c.root == kNoNode || c.usedFrame + kChunkIdleFrames > outputFrame_) continue;
    mesh_.node(c.root).drawnChunk = kNoNode;
    c = DrawnChunk{};  // its memory goes: an idle chunk is not coming back soon
    freeChunks_.push_back(slot);
  }
}

void DrawnChunks::release() {
  for (uint32_t slot : mesh_.takeReleasedChunks()) {
    chunks_[slot] = DrawnChunk{};
    freeChunks_.push_back(slot);
  }
}

void DrawnChunks::remap(const RoamRenumbering& renumbering) {
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
