// The classify stage for cluster sizes 1, 2, 4, 8, 16 — the core seed's fig. 9 experiment
// (../shared/seeds/001_3eca9f2c7752e4fb.txt §3.4: clustered seeding, rendering off): the
// same seed triangles (tests/support/classify_scene.h: 6 889 triangles, 0.3 … 256 plants each,
// ~0.4 M plants) classified by
//   - BM_ClassifyCpu/C: the CPU reference (vegetation/plant_seeding.h), one thread;
//   - BM_ClassifyGpu/C: the classify pass (render/classify_pass.h) on the chosen device, timed
//     by GPU timestamps around its dispatches (manual time), upload of the triangles included.
// Counters: clusters/s (species lookups — seeds of cluster 0 and further clusters — the work
// clustering saves), plants/s, and the
// groups appended. The clustered/unclustered ratio is BM_…/8 against BM_…/1 of the same run.
//
//   build/release/bench/bench_classify [--benchmark_filter=Gpu] [VEGSTREAM_DEVICE=name]

#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "render/classify_pass.h"
#include "render/context.h"
#include "render/gpu_resources.h"
#include "render/gpu_timer.h"
#include "tests/support/classify_scene.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace {

using namespace vegstream;

constexpr uint32_t kLayers = 2;
constexpr float kSpacing = 3.0f;  // 83 × 83 triangles

const testing::ClassifyScene& scene() {
  static const testing::ClassifyScene s = testing::makeClassifyScene(kLayers, kSpacing);
  return s;
}

const std::vector<std::vector<uint8_t>>& maps() {
  static const std::vector<std::vector<uint8_t>> m = {testing::classifyBaseMap(1), testing::classifyBaseMap(2)};
  return m;
}

void BM_ClassifyCpu(benchmark::State& state) {
  const auto size = static_cast<uint32_t>(state.range(0));
  const vegetation::SpeciesCatalog& catalog = vegetation::defaultSpeciesCatalog();
  const testing::ClassifyScene& s = scene();
  std::vector<vegetation::BaseColourAt> colours;
  for (const auto& t : s.gpu) colours.push_back(testing::classifyColour(t, maps()));
  uint64_t clusters = 0, plants = 0, groups = 0;
  std::vector<vegetation::PlantCluster> out;
  for (auto _ : state) {
    out.clear();
    for (size_t i = 0; i < s.cpu.size(); ++i)
      vegetation::classifyTriangle(s.cpu[i], static_cast<uint32_t>(i), catalog, {size}, colours[i], out);
    benchmark::DoNotOptimize(out.data());
  }
  for (const auto& t : s.cpu) clusters += vegetation::classifyItems(t.plantCount, size);
  for (const auto& g : out) plants += g.seedCount;
  groups = out.size();
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["clusters/s"] =
      benchmark::Counter(static_cast<double>(clusters) * iterations, benchmark::Counter::kIsRate);
  state.counters["plants/s"] =
      benchmark::Counter(static_cast<double>(plants) * iterations, benchmark::Counter::kIsRate);
  state.counters["groups"] = static_cast<double>(groups);
  state.counters["plants"] = static_cast<double>(plants);
}

struct Gpu {
  std::unique_ptr<render::Context> ctx;
  render::GpuImage imagery;
  std::unique_ptr<render::ClassifyPass> pass;
  std::unique_ptr<render::GpuTimer> timer;
};

Gpu* gpu() {
  static std::unique_ptr<Gpu> g = [] {
    auto out = std::make_unique<Gpu>();
    render::ContextOptions o;
    if (const char* d = std::getenv("VEGSTREAM_DEVICE")) o.deviceName = d;
    auto created = render::Context::create(o);
    if (!created) return std::unique_ptr<Gpu>();
    out->ctx = std::move(*created);
    const render::Context& ctx = *out->ctx;
    out->imagery = render::createImageArray(
        ctx, {testing::kClassifyTile, testing::kClassifyTile}, kLayers, VK_FORMAT_R8G8B8A8_SRGB,
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "bench imagery", 1, VK_FORMAT_R8G8B8A8_UNORM);
    const VkDeviceSize tileBytes = maps()[0].size();
    render::GpuBuffer staging = render::createBuffer(ctx, tileBytes * kLayers, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                     render::MemoryUse::HostUpload, "bench staging");
    for (uint32_t l = 0; l < kLayers; ++l)
      std::memcpy(static_cast<uint8_t*>(staging.mapped) + l * tileBytes, maps()[l].data(), tileBytes);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      for (uint32_t l = 0; l < kLayers; ++l) render::recordImageUpload(cmd, staging, out->imagery, l, l * tileBytes);
    });
    out->pass = std::make_unique<render::ClassifyPass>(ctx, render::ClassifyOptions{1u << 18});
    out->pass->setCatalog(vegetation::defaultSpeciesCatalog());
    out->timer = std::make_unique<render::GpuTimer>(ctx, 2, "bench classify");
    return out;
  }();
  return g.get();
}

void BM_ClassifyGpu(benchmark::State& state) {
  Gpu* g = gpu();
  if (!g) {
    state.SkipWithError("no Vulkan device");
    return;
  }
  const auto size = static_cast<uint32_t>(state.range(0));
  const testing::ClassifyScene& s = scene();
  render::VegetationFigures f;
  for (auto _ : state) {
    g->ctx->submitAndWait([&](VkCommandBuffer cmd) {
      g->timer->begin(cmd);
      g->timer->beginPass(cmd, "classify");
      f = g->pass->record(cmd, 0, s.gpu, size, g->imagery.alternateView.get(), g->imagery.alternateView.get(), false,
                          3 * size, 0, [](render::GpuBuffer&&) {});
      g->timer->endPass(cmd);
      g->timer->end(cmd);
    });
    state.SetIterationTime(g->timer->read().frameMs / 1000.0);
  }
  g->pass->readFigures(0, f);
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["clusters/s"] =
      benchmark::Counter(static_cast<double>(f.clusters) * iterations, benchmark::Counter::kIsRate);
  state.counters["plants/s"] =
      benchmark::Counter(static_cast<double>(f.plantsTotal) * iterations, benchmark::Counter::kIsRate);
  state.counters["groups"] = static_cast<double>(f.groupsTotal);
  state.counters["plants"] = static_cast<double>(f.plantsTotal);
  state.counters["bins"] = static_cast<double>(f.bins);
  state.counters["idle_share"] =
      f.clusterSlots ? 1.0 - static_cast<double>(f.clusters) / static_cast<double>(f.clusterSlots) : 0.0;
  state.SetLabel(g->ctx->info().name);
}

BENCHMARK(BM_ClassifyCpu)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ClassifyGpu)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
