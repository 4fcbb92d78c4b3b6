#include "render/gpu_timer.h"

#include <cassert>

#include "render/vk_check.h"

namespace vegstream::render {
namespace {
// The order of these bits is the order of the values in the query result.
constexpr VkQueryPipelineStatisticFlagBits kStatisticBits[] = {
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT,
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT,
    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT,
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT,
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT,
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT,
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT,
    VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT,
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT,
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT,
    VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT,
};
}  // namespace

GpuTimer::GpuTimer(const Context& ctx, int maxPasses, const std::string& name)
    : ctx_(&ctx), maxQueries_(static_cast<uint32_t>(2 * maxPasses + 2)) {
  VkQueryPoolCreateInfo tci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  tci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  tci.queryCount = maxQueries_;
  VkQueryPool pool;
  vkCheck(vkCreateQueryPool(ctx.device(), &tci, nullptr, &pool), "vkCreateQueryPool(timestamps)");
  timestamps_ = QueryPool(ctx.device(), pool);
  ctx.setName(VK_OBJECT_TYPE_QUERY_POOL, pool, name + " timestamps");

  VkPhysicalDeviceFeatures features;
  vkGetPhysicalDeviceFeatures(ctx.physicalDevice(), &features);
  if (features.pipelineStatisticsQuery) {
    for (auto bit : kStatisticBits) {
      const bool tess = bit == VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT ||
                        bit == VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT;
      const bool geom = bit == VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT ||
                        bit == VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT;
      if ((tess && !features.tessellationShader) || (geom && !features.geometryShader)) continue;
      statisticFlags_ |= static_cast<VkQueryPipelineStatisticFlags>(bit);
    }
    VkQueryPoolCreateInfo sci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    sci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    sci.queryCount = 1;
    sci.pipelineStatistics = statisticFlags_;
    vkCheck(vkCreateQueryPool(ctx.device(), &sci, nullptr, &pool), "vkCreateQueryPool(statistics)");
    statistics_ = QueryPool(ctx.device(), pool);
    ctx.setName(VK_OBJECT_TYPE_QUERY_POOL, pool, name + " pipeline statistics");
  }
}

void GpuTimer::begin(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, timestamps_.get(), 0, maxQueries_);
  if (statistics_) vkCmdResetQueryPool(cmd, statistics_.get(), 0, 1);
  passNames_.clear();
  used_ = 0;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, timestamps_.get(), used_++);
  if (statistics_) vkCmdBeginQuery(cmd, statistics_.get(), 0, 0);
}

void GpuTimer::beginPass(VkCommandBuffer cmd, const std::string& pass) {
  assert(used_ + 3 <= maxQueries_ && "more passes than GpuTimer was made for");
  passNames_.push_back(pass);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, timestamps_.get(), used_++);
}

void GpuTimer::endPass(VkCommandBuffer cmd) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, timestamps_.get(), used_++);
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (statistics_) vkCmdEndQuery(cmd, statistics_.get(), 0);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, timestamps_.get(), used_++);
  recorded_ = true;
}

GpuTimings GpuTimer::read() const {
  GpuTimings out;
  out.perPassMeaningful = !ctx_->info().software;
  if (!recorded_) return out;
  std::vector<uint64_t> ticks(used_);
  vkCheck(vkGetQueryPoolResults(ctx_->device(), timestamps_.get(), 0, used_, ticks.size() * sizeof(uint64_t),
                                ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults(timestamps)");
  const double msPerTick = static_cast<double>(ctx_->properties().limits.timestampPeriod) * 1e-6;
  out.frameMs = static_cast<double>(ticks[used_ - 1] - ticks[0]) * msPerTick;
  for (size_t i = 0; i < passNames_.size(); ++i)
    out.passes.push_back({passNames_[i], static_cast<double>(ticks[2 + 2 * i] - ticks[1 + 2 * i]) * msPerTick});

  if (statistics_) {
    std::vector<uint64_t> values(std::size(kStatisticBits), 0);
    const auto count = static_cast<size_t>(__builtin_popcount(statisticFlags_));
    vkCheck(vkGetQueryPoolResults(ctx_->device(), statistics_.get(), 0, 1, count * sizeof(uint64_t), values.data(),
                                  count * sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults(statistics)");
    // Spread the packed values back onto their bits.
    uint64_t byBit[std::size(kStatisticBits)] = {};
    size_t next = 0;
    for (size_t b = 0; b < std::size(kStatisticBits); ++b)
      if (statisticFlags_ & static_cast<VkQueryPipelineStatisticFlags>(kStatisticBits[b])) byBit[b] = values[next++];
    PipelineStatistics& s = out.statistics;
    s.available = true;
    s.inputVertices = byBit[0];
    s.inputPrimitives = byBit[1];
    s.vertexInvocations = byBit[2];
    s.geometryInvocations = byBit[3];
    s.geometryPrimitives = byBit[4];
    s.clippingInvocations = byBit[5];
    s.clippingPrimitives = byBit[6];
    s.fragmentInvocations = byBit[7];
    s.tessControlPatches = byBit[8];
    s.tessEvaluationInvocations = byBit[9];
    s.computeInvocations = byBit[10];
  }
  return out;
}

}  // namespace vegstream::render
