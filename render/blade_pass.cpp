// The compute blade path (blade_pass.h), core seed 001_3eca9f2c7752e4fb.txt §2.3–2.4, §3.5–3.6.
#include "render/blade_pass.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include "render/descriptors.h"
#include "render/pipeline_builder.h"
#include "render/render_targets.h"
#include "render/vk_check.h"
#include "shaders/blade.vert.h"
#include "shaders/blade_args.comp.h"
#include "shaders/blades.comp.h"
#include "shaders/plant.frag.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::render {
namespace {

// Mirrors shaders/common/blade_layout.glsl.
struct BladeVertexGpu {
  float pos[3];
  uint32_t plant;
  uint32_t colour[2];  // packHalf2x16 (r, g), (b, 0)
  uint32_t blade;
  uint32_t species;  // the catalog index (AOV frames)
};
static_assert(sizeof(BladeVertexGpu) == 32);
struct BladeStateHeader {
  VkDrawIndexedIndirectCommand draw;
  uint32_t reservedVertices, reservedIndices, reservedPlants;
  uint32_t vertexCapacity, indexCapacity, plantCapacity;
  uint32_t droppedPlants;
};
static_assert(sizeof(BladeStateHeader) == 48);
constexpr VkDeviceSize kDispatchOffset = 48, kDispatchStride = 16;
constexpr VkDeviceSize kStateBytes = kDispatchOffset + kSpeciesSlots * kDispatchStride;
constexpr VkDeviceSize kFigureBytes = 5 * sizeof(uint32_t);

// A plant has fewer than 3 indices per vertex (grass: 6n / (2n + 2)) and at least 4 vertices
// (a stone): the index and plant-record ceilings follow from the vertex ceiling.
constexpr uint64_t kIndicesPerVertex = 3, kVerticesPerPlant = 4;

constexpr VkShaderStageFlags kStages =
    VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

VkDescriptorSetLayoutBinding binding(uint32_t b, VkDescriptorType type) { return {b, type, 1, kStages, nullptr}; }

// Most plants the classify pass can put in a triangle's groups: ⌈min(N, C)⌉ seeds of cluster 0
// plus C per further cluster (vegetation/plant_seeding.h).
uint64_t plantBound(const SeedTriangleGpu& t, uint32_t clusterSize) {
  if (t.layer < 0) return 0;
  const uint32_t items = vegetation::classifyItems(t.v0.w, clusterSize);
  if (items == 0) return 0;
  const auto seeds = static_cast<uint32_t>(std::ceil(std::min(t.v0.w, static_cast<float>(clusterSize))));
  return seeds + uint64_t{items - seeds} * clusterSize;
}

}  // namespace

BladeBufferStart chooseBladeBufferStart(bool software, uint64_t deviceLocalBytes, uint64_t allSlotsCeilingBytes) {
  if (software) return BladeBufferStart::Small;
  return allSlotsCeilingBytes <= deviceLocalBytes / 16 ? BladeBufferStart::Full : BladeBufferStart::Half;
}

BladePass::BladePass(const Context& ctx, VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples,
                     uint32_t maxVertices, TaskRunner* tasks)
    : ctx_(&ctx),
      // A storage buffer is bound whole: no larger than the device's maxStorageBufferRange.
      maxVertices_(std::min<uint64_t>(maxVertices, ctx.properties().limits.maxStorageBufferRange /
                                                       sizeof(BladeVertexGpu))),
      maxIndices_(std::min<uint64_t>(kIndicesPerVertex * maxVertices_,
                                     ctx.properties().limits.maxStorageBufferRange / sizeof(uint32_t)) /
                  6 * 6),
      maxPlants_(std::max<uint64_t>(maxVertices_ / kVerticesPerPlant, 1)) {
  assert(maxVertices >= 6);
  createPipelines(frameLayout, samples);
  createSlots(tasks);
}

void BladePass::createPipelines(VkDescriptorSetLayout frameLayout, VkSampleCountFlagBits samples) {
  const Context& ctx = *ctx_;
  // Set 1: the plant pipelines' inputs (shaders/common/plant_common.glsl); set 2: the blades.
  const VkDescriptorSetLayoutBinding inputs[] = {
      binding(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER), binding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      binding(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), binding(3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
      binding(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)};
  inputLayout_ = createLayout(ctx, inputs, "blade input set layout");
  // Binding 1 (per-plant records) went with lighting per vertex: nothing reads them.
  VkDescriptorSetLayoutBinding blades[5];
  for (uint32_t b = 0; b < 5; ++b) blades[b] = binding(b == 0 ? 0 : b + 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  bladeLayout_ = createLayout(ctx, blades, "blade set layout");
  constexpr auto slots = static_cast<uint32_t>(ClassifyPass::kSlots);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slots},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 8 * slots},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * slots}};
  pool_ = createPool(ctx, sizes, 2 * slots, "blade pool");
  const VkPushConstantRange push{kStages, 0, sizeof(PlantPush)};
  const VkDescriptorSetLayout sets[] = {frameLayout, inputLayout_.get(), bladeLayout_.get()};
  layout_ = createPipelineLayout(ctx, sets, {&push, 1}, "blade pipeline layout");
  expand_ = createComputePipeline(ctx, layout_.get(), spv_blades_comp, "blade expansion pipeline");
  args_ = createComputePipeline(ctx, layout_.get(), spv_blade_args_comp, "blade arguments pipeline");

  GraphicsPipelineDesc desc;
  desc.name = "blade draw pipeline";
  desc.stages = {{VK_SHADER_STAGE_VERTEX_BIT, spv_blade_vert}, {VK_SHADER_STAGE_FRAGMENT_BIT, spv_plant_frag}};
  desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  desc.cullMode = VK_CULL_MODE_NONE;  // blades are two-sided
  desc.samples = samples;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.layout = layout_.get();
  draw_ = createGraphicsPipeline(ctx, desc);
}

void BladePass::createSlots(TaskRunner* tasks) {
  const Context& ctx = *ctx_;
  const BladeBufferStart start = chooseBladeBufferStart(
      ctx.info().software, ctx.info().deviceLocalBytes,
      slots_.size() * (maxVertices_ * sizeof(BladeVertexGpu) + maxIndices_ * sizeof(uint32_t)));
  for (size_t i = 0; i < slots_.size(); ++i) {
    Slot& s = slots_[i];
    const std::string tag = " (slot " + std::to_string(i) + ")";
    s.inputSet = allocateDescriptorSet(ctx, pool_.get(), inputLayout_.get(), "blade input set" + tag);
    s.bladeSet = allocateDescriptorSet(ctx, pool_.get(), bladeLayout_.get(), "blade set" + tag);
    // Transfer source: Renderer::readBladeVertices copies them out for the tests.
    // Transfer destination: a Full start fills a word of each before the first frame.
    constexpr VkDeviceSize kSmall = 64 * 1024;  // GrowingBuffer's own default start
    const VkDeviceSize vertexCeiling = maxVertices_ * sizeof(BladeVertexGpu), indexCeiling = maxIndices_ * sizeof(uint32_t);
    const auto first = [&](VkDeviceSize ceiling) {
      return start == BladeBufferStart::Full ? ceiling
             : start == BladeBufferStart::Half ? std::max(kSmall, ceiling / 2)
                                                : kSmall;
    };
    s.vertices = GrowingBuffer(
        ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        MemoryUse::DeviceLocal, "blade vertices" + tag, tasks, first(vertexCeiling));
    s.indices = GrowingBuffer(
        ctx, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        MemoryUse::DeviceLocal, "blade indices" + tag, tasks, first(indexCeiling));
    if (start == BladeBufferStart::Full) {
      const auto nothingToRetire = [](GpuBuffer&&) { assert(false && "a first buffer retires nothing"); };
      s.vertices.ensure(vertexCeiling, vertexCeiling, nothingToRetire);
      s.indices.ensure(indexCeiling, indexCeiling, nothingToRetire);
    }
    s.state = createBuffer(
        ctx, kStateBytes,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        MemoryUse::DeviceLocal, "blade state" + tag);
    s.figures = createBuffer(ctx, kFigureBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostReadback,
                             "blade figures" + tag);
    std::memset(s.figures.mapped, 0, kFigureBytes);
  }
  if (start == BladeBufferStart::Full)
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      for (Slot& s : slots_)
        for (VkBuffer b : {s.vertices.get(), s.indices.get()}) vkCmdFillBuffer(cmd, b, 0, 4, 0);
    });
}

void BladePass::setCatalog(const vegetation::SpeciesCatalog& catalog) {
  maxHeightM_ = 0.0f;
  for (const vegetation::Species& sp : catalog.species) maxHeightM_ = std::max(maxHeightM_, sp.heightM.max);
}

BladePass::Bound BladePass::bound(std::span<const SeedTriangleGpu> triangles, uint32_t clusterSize,
                                  const PlantDrawOptions& o) const {
  Bound b;
  for (const SeedTriangleGpu& t : triangles) {
    const uint64_t plants = plantBound(t, clusterSize);
    if (plants == 0) continue;
    // The triangle's most segments: common/plant_lod.glsl with the tallest species' radius (a
    // larger radius, a nearer distance, more segments) and the distance shrunk by 0.1 % so float
    // rounding on the GPU never gives more.
    uint64_t n = o.maxSegments;
    if (!o.fullDetail) {
      const glm::vec3 a(t.v0), b1(t.v1), c(t.v2), centre = (a + b1 + c) / 3.0f;
      const double radius =
          std::max({glm::length(a - centre), glm::length(b1 - centre), glm::length(c - centre)}) + double(maxHeightM_);
      const double d = std::max(double(glm::length(centre)) - radius, 0.0) / o.lodDistanceM * 0.999;
      const double segments = std::ceil(o.maxSegments / std::pow(std::max(d, 1.0), 2.0));
      n = static_cast<uint64_t>(std::clamp(segments, 1.0, double(o.maxSegments)));
    }
    // Per plant at most a flower's stem strip and head, and its shadow (blades.comp plantSize).
    b.plants += plants;
    b.vertices += plants * (4 * n + 12);
    b.indices += plants * (12 * n + 12);
  }
  return b;
}

void BladePass::ensureCapacity(Slot& s, const Bound& need, const RetireBuffer& retire) {
  const uint64_t vertices = std::min(need.vertices, maxVertices_);
  const uint64_t indices = std::min(need.indices, maxIndices_);
  // Grown ahead (on the runner when there is one), never past the ceiling (which keeps them
  // within maxStorageBufferRange).
  s.vertices.ensure(vertices * sizeof(BladeVertexGpu), maxVertices_ * sizeof(BladeVertexGpu), retire);
  s.indices.ensure(indices * sizeof(uint32_t), maxIndices_ * sizeof(uint32_t), retire);
  // What the buffers hold (grownSize may give more than asked), within the ceiling; indices a
  // whole number of quads, so the clamped draw never splits a triangle.
  s.vertexCapacity = static_cast<uint32_t>(std::min<uint64_t>(s.vertices.size() / sizeof(BladeVertexGpu), maxVertices_));
  // Plants are numbered (the vertex's plant word), not stored: the count follows the bound.
  s.plantCapacity = static_cast<uint32_t>(std::min(need.plants, maxPlants_));
  s.indexCapacity = static_cast<uint32_t>(std::min<uint64_t>(s.indices.size() / sizeof(uint32_t), maxIndices_) / 6 * 6);
}

void BladePass::writeSets(Slot& s, int slot, const ClassifyPass& classify, const PlantPass& plants,
                          VkImageView imagery) {
  writeUniformBuffer(*ctx_, s.inputSet, classify.species(), sizeof(SpeciesBlock), 0);
  writeStorageBuffer(*ctx_, s.inputSet, classify.triangles(slot), 1);
  writeStorageBuffer(*ctx_, s.inputSet, classify.records(slot), 2);
  writeSampledImage(*ctx_, s.inputSet, plants.tableSampler(), plants.tableView(), 3);
  writeSampledImage(*ctx_, s.inputSet, plants.imagerySampler(), imagery, 4);
  writeStorageBuffer(*ctx_, s.bladeSet, s.vertices.get(), 0);
  writeStorageBuffer(*ctx_, s.bladeSet, s.indices.get(), 2);
  writeStorageBuffer(*ctx_, s.bladeSet, s.state.get(), 3);
  writeStorageBuffer(*ctx_, s.bladeSet, classify.indirect(slot), 4);
  writeStorageBuffer(*ctx_, s.bladeSet, s.figures.get(), 5);
}

void BladePass::recordExpand(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet, const ClassifyPass& classify,
                             const PlantPass& plants, std::span<const SeedTriangleGpu> triangles, uint32_t clusterSize,
                             VkImageView imagery, const PlantDrawOptions& options, const RetireBuffer& retire) {
  assert(options.maxSegments >= 1 && options.maxSegments <= 16);
  Slot& s = slots_[size_t(slot)];
  const uint32_t mask = bladeMask(classify);
  s.expanded = mask != 0 && classify.triangles(slot) != VK_NULL_HANDLE;
  if (!s.expanded) return;
  ensureCapacity(s, bound(triangles, clusterSize, options), retire);

  // The slot's previous frame has finished (the renderer waited on its fence): its sets are free.
  writeSets(s, slot, classify, plants, imagery);

  // Counters cleared, capacities set; the draw's instance count is 1.
  BladeStateHeader header{};
  header.draw.instanceCount = 1;
  header.vertexCapacity = s.vertexCapacity;
  header.indexCapacity = s.indexCapacity;
  header.plantCapacity = s.plantCapacity;
  vkCmdUpdateBuffer(cmd, s.state.get(), 0, sizeof(header), &header);
  // After the header's update and the classify pass's records and draws.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  const VkDescriptorSet sets[] = {frameSet, s.inputSet, s.bladeSet};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 3, sets, 0, nullptr);
  PlantPush push = plants.pushFor(mask, classify, options);  // species: the mask, for the arguments
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, args_.get());
  vkCmdPushConstants(cmd, layout_.get(), kStages, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, 1, 1, 1);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, expand_.get());
  for (uint32_t sp = 0; sp < classify.speciesCount(); ++sp) {
    if (!((mask >> sp) & 1u)) continue;
    push = plants.pushFor(sp, classify, options);
    vkCmdPushConstants(cmd, layout_.get(), kStages, 0, sizeof(push), &push);
    vkCmdDispatchIndirect(cmd, s.state.get(), kDispatchOffset + VkDeviceSize{sp} * kDispatchStride);
  }
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  push = plants.pushFor(mask, classify, options);
  push.flags |= kPlantFlagArgsFinish;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, args_.get());
  vkCmdPushConstants(cmd, layout_.get(), kStages, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, 1, 1, 1);
  // Vertices, records, indices and the draw to the graphics stages; the figures to the host.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT |
                    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT |
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
  s.drawPush = plants.pushFor(0, classify, options);  // the fragment stage reads flags (samples)
}

void BladePass::recordDraw(VkCommandBuffer cmd, int slot, VkDescriptorSet frameSet) const {
  const Slot& s = slots_[size_t(slot)];
  if (!s.expanded) return;
  const VkDescriptorSet sets[] = {frameSet, s.inputSet, s.bladeSet};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 3, sets, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, draw_.get());
  vkCmdPushConstants(cmd, layout_.get(), kStages, 0, sizeof(s.drawPush), &s.drawPush);
  vkCmdBindIndexBuffer(cmd, s.indices.get(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexedIndirect(cmd, s.state.get(), 0, 1, sizeof(VkDrawIndexedIndirectCommand));
}

void BladePass::readFigures(int slot, VegetationFigures& f) const {
  const Slot& s = slots_[size_t(slot)];
  if (!s.expanded) return;
  const auto* c = static_cast<const uint32_t*>(s.figures.mapped);
  f.bladeCounts = true;
  f.bladeVertices = std::min<uint64_t>(c[0], s.vertexCapacity);
  f.bladesDropped = c[3];
  f.bladeTriangles = c[4] / 3;
}

uint64_t BladePass::writtenVertices(int slot) const {
  const Slot& s = slots_[size_t(slot)];
  if (!s.expanded) return 0;
  return std::min<uint64_t>(static_cast<const uint32_t*>(s.figures.mapped)[0], s.vertexCapacity);
}

uint64_t BladePass::gpuBytes() const {
  uint64_t n = 0;
  for (const Slot& s : slots_) n += s.vertices.size() + s.indices.size() + s.state.size;
  return n;
}

}  // namespace vegstream::render
