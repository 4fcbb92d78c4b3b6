// Imagery uploads through the terrain pass's staging ring: frames with K tiles of 256 × 256 RGBA
// copied into the imagery array against frames with none, on whatever device is chosen
// (VEGSTREAM_DEVICE: a substring of its name; default: the first hardware GPU, else lavapipe).
// Upload MB/s = K · 256 KiB / (frame time with K − frame time with 0), read side by side from one run.

#include <cstdlib>
#include <vector>

#include <benchmark/benchmark.h>

#include "render/renderer.h"

namespace {
using namespace vegstream;

std::unique_ptr<render::Renderer>& renderer() {
  static std::unique_ptr<render::Renderer> r = [] {
    render::RendererOptions o;
    o.width = 64;
    o.height = 64;
    o.msaa = 1;
    if (const char* d = std::getenv("VEGSTREAM_DEVICE")) o.context.deviceName = d;
    auto created = render::Renderer::create(o);
    if (!created) std::abort();
    if (!(*created)->setImageryLayers(256)) std::abort();
    return std::move(*created);
  }();
  return r;
}

void BM_FrameWithImageryUploads(benchmark::State& state) {
  const auto tiles = static_cast<uint32_t>(state.range(0));
  std::vector<uint8_t> rgba(size_t{render::kImageryTileSize} * render::kImageryTileSize * 4, 128);
  std::vector<render::ImageryUpload> uploads;
  uint32_t layer = 0;
  render::FrameRequest req;
  req.camera.position = {0, 0, 100};
  for (auto _ : state) {
    uploads.clear();
    for (uint32_t i = 0; i < tiles; ++i) uploads.push_back({layer++ % 256, rgba});
    req.imageryUploads = uploads;
    auto f = renderer()->renderFrame(req);
    if (!f) state.SkipWithError(f.error().message.c_str());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * tiles * static_cast<int64_t>(rgba.size()));
  state.SetLabel(renderer()->device().name);
}
BENCHMARK(BM_FrameWithImageryUploads)->Arg(0)->Arg(8)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
