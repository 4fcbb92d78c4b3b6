#pragma once
// A dataset opened for flying: its heights and imagery loaded into a terrain mesh coloured by
// the imagery, the renderer that draws it, and the conversion from flight samples to render
// frames. Until streaming (issue 5) and ROAM (issue 6) arrive, the whole dataset is loaded at
// one zoom at open(): the finest whose mesh fits SceneOptions::maxMeshTriangles for heights,
// the finest whose mosaic fits SceneOptions::maxImageryPixels for colour.
//
// Contract: open() checks the dataset and every renderer option before loading anything, and
// returns user mistakes as errors whose message names the dataset or option.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "flight/ground_height.h"
#include "flight/path_sampler.h"
#include "geo/bounds.h"
#include "geo/local_frame.h"
#include "render/renderer.h"

namespace vegstream::flight {

struct SceneOptions {
  std::filesystem::path dataset;          // a dataset directory (dataset.json, DESIGN.md)
  render::RendererOptions renderer;
  uint64_t maxMeshTriangles = 800'000;    // picks the height zoom (Zion: zoom 11, 61 m pixels)
  uint64_t maxImageryPixels = 16'000'000; // picks the imagery zoom
  Logger logger;                          // may be null
};

struct SceneInfo {
  std::string datasetName;
  geo::GeoBounds bounds;
  int heightZoom = 0;
  int imageryZoom = -1;        // −1: the dataset has no imagery (terrain coloured by height)
  uint64_t meshTriangles = 0;
  uint64_t cpuBytes = 0;       // heights + imagery + mesh held on the CPU
  uint64_t gpuBytes = 0;       // vertex, index and imagery memory on the GPU
  double loadMs = 0.0;
};

class Scene {
 public:
  static Result<std::unique_ptr<Scene>> open(const SceneOptions& options);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  render::Renderer& renderer();
  const SceneInfo& info() const;
  const geo::LocalFrame& frame() const;  // ENU at the dataset's centre, height 0

  // Ground height (m MSL) under a point, bilinear over the loaded heights; NaN outside the data.
  double groundHeight(double latDeg, double lonDeg) const;
  GroundHeight groundFunction() const;  // the same, for PathSampler

  // The render request for a camera at a flight sample (camera in the scene's frame, the
  // scene's lighting); read-backs and presenting are the caller's to set.
  render::FrameRequest frameRequest(const FlightSample& sample) const;

  struct Impl;

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vegstream::flight
