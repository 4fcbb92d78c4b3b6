// The terrain's GPU vertex pool's bookkeeping (terrain_chunk_cache.h).

#include "render/terrain_chunk_cache.h"

#include <algorithm>
#include <cassert>
#include <stdexcept>

namespace vegstream::render {
namespace {

// The smallest class whose ranges hold `vertices`.
int sizeClassFor(uint32_t vertices) {
  int k = 0;
  uint64_t size = TerrainChunkCache::kSmallestRange;
  while (size < vertices) {
    size *= 2;
    ++k;
  }
  return k;
}

uint64_t classSize(int k) { return uint64_t{TerrainChunkCache::kSmallestRange} << k; }

}  // namespace

TerrainChunkCache::TerrainChunkCache(uint32_t framesInFlight, uint64_t idleFrames)
    : framesInFlight_(framesInFlight), idleFrames_(idleFrames) {
  assert(framesInFlight >= 1 && idleFrames >= 1);
}

void TerrainChunkCache::beginFrame() {
  ++frame_;
  figures_ = {};
  size_t n = 0;  // retired_ is in frame order: the reusable ones lead
  while (n < retired_.size() && retired_[n].reusableFrame <= frame_) {
    free_[static_cast<size_t>(retired_[n].sizeClass)].push_back(retired_[n].firstVertex);
    ++n;
  }
  retired_.erase(retired_.begin(), retired_.begin() + static_cast<std::ptrdiff_t>(n));
}

uint32_t TerrainChunkCache::allocate(uint32_t vertices, int& sizeClass) {
  sizeClass = sizeClassFor(vertices);
  if (sizeClass >= kSizeClasses) throw std::length_error("terrain vertex pool: a mesh of too many vertices");
  std::vector<uint32_t>& list = free_[static_cast<size_t>(sizeClass)];
  if (!list.empty()) {
    const uint32_t first = list.back();
    list.pop_back();
    return first;
  }
  const uint64_t first = end_;
  if (first + classSize(sizeClass) > UINT32_MAX) throw std::length_error("terrain vertex pool: over 2^32 vertices");
  end_ += classSize(sizeClass);
  return static_cast<uint32_t>(first);
}

void TerrainChunkCache::retire(uint32_t firstVertex, int sizeClass) {
  retired_.push_back({firstVertex, sizeClass, frame_ + framesInFlight_});
}

ChunkPlacement TerrainChunkCache::place(uint64_t id, uint64_t version, uint32_t vertices) {
  ++figures_.chunksDrawn;
  auto [it, added] = resident_.try_emplace(id);
  Resident& r = it->second;
  // The same id and version keep their vertices (terrain_mesh.h); a chunk that broke that by
  // growing is placed anew rather than written past its range.
  if (!added && r.version == version && vertices <= classSize(r.sizeClass)) {
    r.usedFrame = frame_;
    return {r.firstVertex, false};
  }
  // New, or moved: a new range, so a frame in flight still reads the old one as it was.
  if (!added) retire(r.firstVertex, r.sizeClass);
  r.firstVertex = allocate(std::max<uint32_t>(vertices, 1), r.sizeClass);
  r.version = version;
  r.usedFrame = frame_;
  ++figures_.chunksUploaded;
  figures_.verticesUploaded += vertices;
  return {r.firstVertex, true};
}

uint32_t TerrainChunkCache::placeTransient(uint32_t vertices) {
  int sizeClass = 0;
  const uint32_t first = allocate(std::max<uint32_t>(vertices, 1), sizeClass);
  retire(first, sizeClass);
  figures_.verticesUploaded += vertices;
  return first;
}

void TerrainChunkCache::endFrame() {
  figures_.chunksResident = resident_.size();
  // The idle chunks are looked for every idleFrames / 8 frames: a walk over every resident chunk
  // (a node of the map each) every frame showed in the frame thread's profile (render/README.md).
  const uint64_t every = std::max<uint64_t>(1, idleFrames_ / 8);
  if (frame_ % every != 0) return;
  for (auto it = resident_.begin(); it != resident_.end();) {
    if (frame_ - it->second.usedFrame >= idleFrames_) {
      retire(it->second.firstVertex, it->second.sizeClass);
      it = resident_.erase(it);
    } else {
      ++it;
    }
  }
  figures_.chunksResident = resident_.size();
}

}  // namespace vegstream::render
