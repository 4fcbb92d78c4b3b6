// The terrain vertex pool's bookkeeping (render/terrain_chunk_cache.h): a chunk is uploaded once
// while its id and version stay, a moved chunk gets a new range, and no range is handed out
// again while a frame in flight may still read it. No GPU.

#include "render/terrain_chunk_cache.h"

#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace vegstream::render {
namespace {

terrain::TerrainChunk chunk(uint64_t id, uint64_t version, size_t vertices) {
  terrain::TerrainChunk c;
  c.id = id;
  c.version = version;
  c.vertices.resize(vertices);
  return c;
}

TEST(TerrainChunkCache, AChunkIsUploadedOnceWhileItsIdAndVersionStay) {
  TerrainChunkCache cache(3, 64);
  const terrain::TerrainChunk a = chunk(1, 0, 40), b = chunk(2, 0, 70);
  cache.beginFrame();
  const ChunkPlacement pa = cache.place(a), pb = cache.place(b);
  cache.endFrame();
  EXPECT_TRUE(pa.upload);
  EXPECT_TRUE(pb.upload);
  EXPECT_NE(pa.firstVertex, pb.firstVertex);
  EXPECT_EQ(cache.figures().chunksUploaded, 2u);
  EXPECT_EQ(cache.figures().verticesUploaded, 110u);
  EXPECT_EQ(cache.capacity(), 64u + 128u) << "ranges of 64 · 2^k vertices";
  for (int frame = 0; frame < 10; ++frame) {
    cache.beginFrame();
    const ChunkPlacement again = cache.place(a);
    cache.endFrame();
    EXPECT_FALSE(again.upload);
    EXPECT_EQ(again.firstVertex, pa.firstVertex);
    EXPECT_EQ(cache.figures().chunksDrawn, 1u);
    EXPECT_EQ(cache.figures().chunksUploaded, 0u);
    EXPECT_EQ(cache.figures().verticesUploaded, 0u);
  }
}

TEST(TerrainChunkCache, AMovedChunkGetsANewRangeAndTheOldOneWaitsForTheFramesInFlight) {
  constexpr uint32_t kInFlight = 3;
  TerrainChunkCache cache(kInFlight, 64);
  cache.beginFrame();
  const uint32_t first = cache.place(chunk(7, 0, 50)).firstVertex;
  cache.endFrame();
  cache.beginFrame();  // frame 2: the chunk's vertices moved
  const ChunkPlacement moved = cache.place(chunk(7, 1, 50));
  cache.endFrame();
  EXPECT_TRUE(moved.upload);
  EXPECT_NE(moved.firstVertex, first) << "frame 1, maybe in flight, still reads the old range";
  // New chunks of the same size: the old range comes back only at frame 2 + 3.
  std::set<uint32_t> handedOut;
  for (uint64_t frame = 3; frame <= 6; ++frame) {
    cache.beginFrame();
    const uint32_t at = cache.place(chunk(100 + frame, 0, 50)).firstVertex;
    cache.endFrame();
    if (frame < 2 + kInFlight) {
      EXPECT_NE(at, first) << "frame " << frame;
    }
    handedOut.insert(at);
  }
  EXPECT_TRUE(handedOut.count(first)) << "reused once the frames in flight are done";
}

TEST(TerrainChunkCache, IdleChunksAndTransientRangesAreGivenUp) {
  TerrainChunkCache cache(2, 4);
  cache.beginFrame();
  cache.place(chunk(1, 0, 64));
  const uint32_t own = cache.placeTransient(100);
  cache.endFrame();
  EXPECT_EQ(cache.figures().verticesUploaded, 164u);
  EXPECT_EQ(cache.figures().chunksResident, 1u);
  for (int i = 0; i < 4; ++i) {
    cache.beginFrame();
    cache.endFrame();
  }
  EXPECT_EQ(cache.figures().chunksResident, 0u) << "not drawn for 4 frames";
  // Drawn again: uploaded again. The pool does not grow: freed ranges are reused.
  const uint64_t capacity = cache.capacity();
  for (int i = 0; i < 3; ++i) {
    cache.beginFrame();
    cache.endFrame();
  }
  cache.beginFrame();
  EXPECT_TRUE(cache.place(chunk(1, 0, 64)).upload);
  EXPECT_EQ(cache.placeTransient(100), own);
  cache.endFrame();
  EXPECT_EQ(cache.capacity(), capacity);
}

TEST(TerrainChunkCache, AChunkThatGrowsUnderItsIdIsPlacedAnew) {
  TerrainChunkCache cache(3, 64);
  cache.beginFrame();
  const uint32_t first = cache.place(chunk(5, 0, 60)).firstVertex;
  const uint32_t next = cache.place(chunk(6, 0, 60)).firstVertex;
  cache.endFrame();
  ASSERT_EQ(next, first + 64) << "neighbours in the pool";
  cache.beginFrame();
  const ChunkPlacement grown = cache.place(chunk(5, 0, 100));  // a producer bug: more vertices, same id and version
  cache.endFrame();
  EXPECT_TRUE(grown.upload);
  EXPECT_NE(grown.firstVertex, first) << "not written over chunk 6's range";
}

TEST(TerrainChunkCache, TheSameCallsGiveTheSameRanges) {
  const auto run = [] {
    TerrainChunkCache cache(3, 8);
    std::vector<std::pair<uint32_t, bool>> out;
    for (uint64_t frame = 0; frame < 40; ++frame) {
      cache.beginFrame();
      for (uint64_t id = frame % 7; id < 30; id += 3) {
        const ChunkPlacement p = cache.place(chunk(id, frame / 5, 10 + id * 7));
        out.emplace_back(p.firstVertex, p.upload);
      }
      out.emplace_back(cache.placeTransient(static_cast<uint32_t>(frame * 13)), true);
      cache.endFrame();
    }
    return out;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace vegstream::render
