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
    state_.emplace_back();
  } else {
    slot = freeChunks_.back();
    freeChunks_.pop_back();
  }
  // While a compaction's copy reads the nodes the attachment waits: the end of the compaction
  // attaches every chunk to its root again (remap: state_[slot].root, set below).
  if (attach) mesh_.node(t).drawnChunk = slot;
  state_[slot].root = kNoNode;
  return slot;
}

void DrawnChunks::draw(const ChunkPass& pass, uint32_t t, int piece) {
  const geo::TileId& tile = pass.pieces->tiles()[size_t(piece)];
  const uint32_t slot = slotFor(t, pass.attach);
  ChunkState& state = state_[slot];
  state.usedFrame = outputFrame_;
  state.rebuild = state.root != t || mesh_.node(t).drawnStamp > state.builtStamp || !(state.piece == tile);
  if (state.rebuild) {
    state.root = t;
    state.piece = tile;
    state.builtStamp = chunkEpoch_;
    TerrainChunk& mesh = chunks_[slot].mesh;
    mesh.id = nextChunkId_++;
    mesh.version = 0;
    ++figures_.chunksBuilt;
  } else {
    ++figures_.chunksReused;
  }
  draws_.push_back({slot, piece});
  if (options_.tasks) return;  // prepared on the workers, appended in order (finish)
  // One thread: prepared and appended at once, while the chunk is still in the cache.
  if (chunkScratch_.empty()) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}});
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
  while (chunkScratch_.size() < blocks) chunkScratch_.push_back({ChunkVertexMap(options_.chunkMaxLeaves), {}});
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
  ChunkState& state = state_[d.slot];
  if (!state.rebuild && !state.morphing) return;  // reused as it was: its record is not read
  DrawnChunk& chunk = chunks_[d.slot];
  const glm::dvec3& origin = (*pass.meshes)[size_t(d.piece)].origin;
  if (state.rebuild)
    rebuild(pass, d.slot, origin, scratch, counts);
  else
    move(pass, chunk, origin, counts);
  state.morphing = !chunk.morphing.empty();
  keepBounds(chunk.mesh);
  state.drawn = TerrainChunkDraw::of(chunk.mesh);
}

void DrawnChunks::rebuild(const ChunkPass& pass, uint32_t slot, const glm::dvec3& origin, ChunkScratch& scratch,
                          EmitCounts& counts) {
  DrawnChunk& chunk = chunks_[slot];
  const ChunkState& state = state_[slot];
  chunk.mesh.vertices.clear();
  chunk.mesh.indices.clear();
  chunk.morphing.clear();
  scratch.map.clear();
  const LeafSink sink{.vertices = &chunk.mesh.vertices,
                      .indices = &chunk.mesh.indices,
                      .origin = origin,
                      .tile = &state.piece,
                      .stamps = nullptr,
                      .frame = 0,
                      .stamp = 0,
                      .chunkVertices = &scratch.map,
                      .counts = &counts,
                      .morphing = &chunk.morphing};
  collect(state.root, scratch.leaves);
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

void DrawnChunks::append(const ChunkPass& pass, const ChunkDraw& d) {
  const TerrainChunkDraw& drawn = state_[d.slot].drawn;
  if (drawn.count == 0) return;                             // no data under it
  (*pass.meshes)[size_t(d.piece)].chunks.push_back(drawn);  // the chunk's record is not read
  figures_.drawnTriangles += drawn.count / 3;
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
  for (uint32_t slot = 0; slot < state_.size(); ++slot) {
    ChunkState& c = state_[slot];
    if (c.root == kNoNode || c.usedFrame + kChunkIdleFrames > outputFrame_) continue;
    mesh_.node(c.root).drawnChunk = kNoNode;
    freeSlot(slot);  // its memory goes: an idle chunk is not coming back soon
  }
}

void DrawnChunks::freeSlot(uint32_t slot) {
  chunks_[slot] = DrawnChunk{};
  state_[slot] = ChunkState{};
  freeChunks_.push_back(slot);
}

void DrawnChunks::release() {
  for (uint32_t slot : mesh_.takeReleasedChunks()) freeSlot(slot);
}

void DrawnChunks::remap(const RoamRenumbering& renumbering) {
  // Chunks whose root was freed are released before compaction: every index here is live.
  auto node = [&](uint32_t i) { return i == kNoNode ? kNoNode : renumbering.nodes[i]; };
  // The compacted nodes hold no chunk (RoamMesh::compact): each is attached to its root again.
  for (uint32_t slot = 0; slot < state_.size(); ++slot) {
    ChunkState& c = state_[slot];
    if (c.root == kNoNode) continue;
    c.root = node(c.root);
    mesh_.node(c.root).drawnChunk = slot;
  }
}

}  // namespace vegstream::terrain
