#pragma once
// Where the terrain's vertices live on the GPU, frame to frame (issue 44 item 2): one vertex pool
// shared by the frame slots, in which each TerrainChunk (terrain_mesh.h; ROAM's drawn chunks)
// keeps its range for as long as its id and version stay the same, so a frame uploads only the
// chunks that are new or whose vertices moved. A mesh's own vertices (not in a chunk) change
// every frame: they get a range for one frame.
//
// This is the bookkeeping only (no graphics API): TerrainPass copies what place() says to upload
// into the ranges it hands out. Contract:
// - Once per frame, beginFrame(), then place() / placeTransient() for everything the frame
//   draws, then endFrame().
// - A range stays untouched while a frame in flight may read it: a range given up in frame F
//   (a chunk's old version, an idle chunk, a frame's own vertices) is handed out again from
//   frame F + framesInFlight on, once the frame slot's fence has seen frame F finish.
// - A chunk not drawn for `idleFrames` frames gives its range up (they are looked for every
//   idleFrames / 8 frames, so within 9/8 × idleFrames); drawn again later, it is uploaded again.
// - Ranges are 64 · 2^k vertices (k ≥ 0), from a free list per size or else from the end of the
//   pool; capacity() is the pool's high-water mark, which the pool's buffer must hold.
// Deterministic: the same sequence of calls gives the same ranges.

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "terrain/terrain_mesh.h"

namespace vegstream::render {

struct ChunkPlacement {
  uint32_t firstVertex = 0;  // where the chunk's vertices are in the pool
  bool upload = false;       // true: this frame must copy them there (new, or moved)
};

struct ChunkCacheFigures {
  uint64_t chunksDrawn = 0, chunksUploaded = 0;  // this frame's
  uint64_t verticesUploaded = 0;                 // chunk and own vertices copied this frame
  uint64_t chunksResident = 0;                   // after endFrame()
};

class TerrainChunkCache {
 public:
  static constexpr uint32_t kSmallestRange = 64;  // vertices
  static constexpr int kSizeClasses = 27;         // up to 64 · 2^26 vertices

  TerrainChunkCache(uint32_t framesInFlight, uint64_t idleFrames);

  void beginFrame();
  // The chunk `id` at `version`, of `vertices` vertices (TerrainChunkDraw's header).
  ChunkPlacement place(uint64_t id, uint64_t version, uint32_t vertices);
  ChunkPlacement place(const terrain::TerrainChunk& chunk) {
    return place(chunk.id, chunk.version, static_cast<uint32_t>(chunk.vertices.size()));
  }
  // `vertices` vertices for this frame only (always uploaded).
  uint32_t placeTransient(uint32_t vertices);
  void endFrame();

  // Vertices the pool must hold: the end of the highest range ever handed out.
  uint64_t capacity() const { return end_; }
  const ChunkCacheFigures& figures() const { return figures_; }

 private:
  struct Resident {
    uint32_t firstVertex = 0;
    int sizeClass = 0;
    uint64_t version = 0;
    uint64_t usedFrame = 0;
  };
  struct Retired {
    uint32_t firstVertex = 0;
    int sizeClass = 0;
    uint64_t reusableFrame = 0;
  };
  uint32_t allocate(uint32_t vertices, int& sizeClass);
  void retire(uint32_t firstVertex, int sizeClass);

  uint32_t framesInFlight_;
  uint64_t idleFrames_;
  uint64_t frame_ = 0;
  uint64_t end_ = 0;
  std::unordered_map<uint64_t, Resident> resident_;  // by chunk id
  std::array<std::vector<uint32_t>, kSizeClasses> free_;
  std::vector<Retired> retired_;  // in frame order
  ChunkCacheFigures figures_;
};

}  // namespace vegstream::render
