#pragma once
// One classify dispatch over a test scene with its groups read back, for the GPU tests of the
// species choice's inputs (classify_ndvi_gpu_test, classify_landcover_gpu_test): the imagery and
// its companion layer uploaded from one staging buffer, the pass recorded with `companionFlags`
// (render/frame_types.h ImageryCompanions::flags), and every group of species 0 … species − 1
// returned as (triangle, cluster, firstSeed) → species. No overflow is expected.

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>
#include <tuple>

#include <gtest/gtest.h>

#include "render/classify_pass.h"
#include "render/context.h"

namespace vegstream::render::testing {

using ClassifyGroups = std::map<std::tuple<uint32_t, uint32_t, uint32_t>, uint32_t>;

struct ClassifyUploads {
  GpuImage& imagery;     // RGBA8 sRGB with a UNORM alternate view, one layer
  GpuImage& companions;  // the companion layer (R8 NDVI, or RG8 NDVI + class), one layer
  GpuBuffer& staging;    // the imagery's bytes at 0, the companions' at companionOffset
  VkDeviceSize companionOffset = 0;
};

inline ClassifyGroups classifyOnce(const Context& ctx, ClassifyPass& pass, const ClassifyUploads& in,
                                   std::span<const SeedTriangleGpu> triangles, uint32_t clusterSize,
                                   uint32_t companionFlags, uint32_t species, GpuBuffer& recordsHost) {
  VegetationFigures f;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    recordImageUpload(cmd, in.staging, in.imagery, 0, 0);
    recordImageUpload(cmd, in.staging, in.companions, 0, in.companionOffset);
    f = pass.record(cmd, 0, triangles, clusterSize, in.imagery.alternateView.get(), in.companions.view.get(),
                    companionFlags, 3 * clusterSize, 0, [](GpuBuffer&&) {});
  });
  pass.readFigures(0, f);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy all{0, 0, recordsHost.size};
    vkCmdCopyBuffer(cmd, pass.records(0), recordsHost.get(), 1, &all);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  EXPECT_FALSE(f.overflow);
  const uint32_t capacity = pass.clustersPerSpecies();
  const auto* records = static_cast<const PlantClusterGpu*>(recordsHost.mapped);
  ClassifyGroups groups;
  for (uint32_t s = 0; s < species; ++s)
    for (uint32_t i = 0; i < std::min(f.groups[s], capacity); ++i) {
      const PlantClusterGpu& r = records[size_t{s} * capacity + i];
      groups[{r.triangle, r.cluster, r.firstSeed}] = s;
    }
  return groups;
}

}  // namespace vegstream::render::testing
