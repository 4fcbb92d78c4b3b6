// The terrain's resident indices (render/terrain_index_pool.h, issue 44 item 2): over frames in
// which chunks are new, moved (a new version), drawn in full or in part, left out and drawn
// again, every index of the frame's index buffer — written by the frame thread or gathered on the
// GPU from the index pool — must name, in the vertex pool, the vertex the CPU mesh names. Each
// vertex's position is unique (chunk id, version, vertex), so a wrong range, a stale upload or a
// wrong rebase shows. On lavapipe, validation on.
#include <cstring>
#include <memory>
#include <vector>

#include "gpu_test_fixture.h"
#include "render/gpu_resources.h"
#include "render/terrain_geometry_buffers.h"

namespace vegstream::render::testing {
namespace {

using terrain::TerrainChunk;
using terrain::TerrainVertex;

// A strip of `quads` quads (2 · quads triangles over 2 · quads + 2 vertices), each vertex at
// (id, version, its index): no two vertices of any chunk or version share a position.
TerrainChunk strip(uint64_t id, uint64_t version, uint32_t quads) {
  TerrainChunk c;
  c.id = id;
  c.version = version;
  for (uint32_t v = 0; v < 2 * quads + 2; ++v)
    c.vertices.push_back({glm::vec3(float(id), float(version), float(v)), glm::vec3(0, 0, 1), 0.0f, glm::vec2(0)});
  for (uint32_t q = 0; q < quads; ++q)
    c.indices.insert(c.indices.end(), {2 * q, 2 * q + 1, 2 * q + 2, 2 * q + 1, 2 * q + 3, 2 * q + 2});
  return c;
}

template <class T>
std::vector<T> readBack(const Context& ctx, VkBuffer src, size_t count) {
  std::vector<T> out(count);
  if (count == 0) return out;
  GpuBuffer host =
      createBuffer(ctx, count * sizeof(T), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "test read-back");
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy copy{0, 0, count * sizeof(T)};
    vkCmdCopyBuffer(cmd, src, host.get(), 1, &copy);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  std::memcpy(out.data(), host.mapped, count * sizeof(T));
  return out;
}

class TerrainIndexGatherTest : public GpuTest {};

TEST_F(TerrainIndexGatherTest, EveryIndexNamesTheMeshsVertexFrameAfterFrame) {
  auto ctx = validatedContext();
  ASSERT_TRUE(ctx);
  std::vector<GpuBuffer> retired;
  const GrowingBuffer::Retire retire = [&](GpuBuffer&& b) { retired.push_back(std::move(b)); };
  {
    TerrainGeometryBuffers buffers(*ctx, nullptr, 64, /*resident=*/true);
    uint64_t gathered = 0, written = 0;
    for (int frame = 0; frame < 12; ++frame) {
      // 40 chunks; every third frame a quarter of them move, and from frame 6 on ids 30… are new.
      std::vector<TerrainChunk> chunks;
      for (uint64_t i = 0; i < 40; ++i) {
        const uint64_t id = frame >= 6 && i >= 30 ? 100 + i : i;
        chunks.push_back(strip(id, i % 4 == 0 ? uint64_t(frame / 3) : 0, 3 + uint32_t(i % 7) * 5));
      }
      terrain::TerrainMesh meshes[2];
      for (int p = 0; p < 2; ++p) {  // own vertices: a triangle per piece, new every frame
        terrain::TerrainMesh& m = meshes[p];
        for (int v = 0; v < 3; ++v)
          m.vertices.push_back(
              {glm::vec3(-1.0f - float(p), float(frame), float(v)), glm::vec3(0, 0, 1), 0.0f, glm::vec2(0)});
        m.indices = {0, 1, 2};
      }
      for (size_t i = 0; i < chunks.size(); ++i) {
        if ((i + size_t(frame)) % 9 == 0) continue;  // left out this frame
        terrain::TerrainMesh& m = meshes[i % 2];
        const TerrainChunk& c = chunks[i];
        m.chunks.push_back(terrain::TerrainChunkDraw::of(c));
      }
      const TerrainDraw draws[2] = {{&meshes[0]}, {&meshes[1]}};
      const uint32_t order[2] = {1, 0};
      const int slot = frame % TerrainGeometryBuffers::kSlots;
      std::vector<PieceRange> ranges;
      ctx->submitAndWait([&](VkCommandBuffer cmd) { ranges = buffers.write(cmd, slot, draws, order, retire); });
      ASSERT_EQ(ranges.size(), 2u);
      const size_t total = ranges[1].firstIndex + ranges[1].indexCount;
      const auto indices = readBack<uint32_t>(*ctx, buffers.indices(slot), total);
      uint32_t highest = 0;
      for (uint32_t i : indices) highest = std::max(highest, i);
      const auto pool = readBack<TerrainVertex>(*ctx, buffers.vertices(slot), size_t{highest} + 1);
      size_t checked = 0, wrong = 0;
      for (size_t k = 0; k < 2; ++k) {
        size_t at = ranges[k].firstIndex;
        terrain::forEachTriangle(*draws[order[k]].mesh,
                                 [&](const TerrainVertex& a, const TerrainVertex& b, const TerrainVertex& c) {
                                   for (const TerrainVertex* v : {&a, &b, &c}) {
                                     ++checked;
                                     if (pool[indices[at++]].position != v->position && ++wrong <= 5)
                                       ADD_FAILURE() << "frame " << frame << ", piece " << k << ", index " << at - 1;
                                   }
                                 });
        EXPECT_EQ(at, size_t{ranges[k].firstIndex} + ranges[k].indexCount);
      }
      EXPECT_EQ(wrong, 0u) << "frame " << frame;
      EXPECT_EQ(checked, total);
      gathered += buffers.gatheredIndices();
      written += total - buffers.gatheredIndices();
    }
    EXPECT_GT(gathered, 3 * written) << "most indices come from the pool, not the frame thread";
    EXPECT_GT(written, 0u) << "the pieces' own";
  }
}

}  // namespace
}  // namespace vegstream::render::testing
