#pragma once
// The streaming and terrain options that `fly` and `record` share (--cpu-budget-mb,
// --gpu-budget-mb, --streaming, --no-look-ahead, --terrain-error-px, --http-cache, --allow-redirects, …), and how
// they become SceneOptions. One definition, so both commands spell and check them alike.

#include <cstdint>
#include <string>

#include "core/result.h"
#include "scene/scene.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct StreamingCli {
  double cpuBudgetMb = 512.0;  // decoded tiles in memory
  double gpuBudgetMb = 256.0;  // imagery tiles on the GPU
  double uploadMbPerFrame = 8.0;
  std::string mode;  // "settled" | "realtime"; empty: the command's default
  bool noLookAhead = false;
  double terrainErrorPx = 2.0;
  int terrainMaxNodes = 384;
  int64_t terrainMaxTriangles = 120000;  // ROAM leaves
  double canopyM = 30.0;                 // tallest plant, for culling
  std::string terrainShading = "auto";  // auto | forward | deferred (render::TerrainShading)
  std::string terrainGeometry = "resident";  // resident | copied (render::RendererOptions::residentTerrain)
  std::string terrainDepthTiles = "vegetation";  // vegetation | all | checked (render::RendererOptions::depthTiles)
  int frameWorkers = 0;                       // scene::SceneOptions::frameWorkers
  double terrainDetail = 1.0;            // close-up detail textures, 0 (bare imagery) … 1
  double seedHorizonM = 250.0;           // seed triangles within this distance (and each species' own)
  std::string httpCache;                 // directory for the on-disk HTTP tile cache; empty: none
  bool allowRedirects = false;           // follow HTTP redirects to other hosts too
  double httpTimeoutS = 30.0;            // one HTTP request, all its retries included
  // Plants (issue 7): density ρ and n_max of eq. 1, cluster size C, species catalog.
  double plantDensity = 0.1;   // ρ: plants per reference pixel² (1080 lines) of projected seed-triangle area
  std::string plantFades = "on";
  double plantMax = 16384.0;   // n_max per seed triangle: a ceiling; the catalog's densities decide
  double plantContour = 0.0;   // α of Belyaev's contour term (terrain::SeedOptions::contourAlpha); 0: off
  int clusterSize = 8;
  std::string species;  // a species catalog JSON file; empty: the default
  bool noPlants = false;
  std::string plantStyle = "plants";  // plants | markers | hidden
  int plantSegments = 5;              // n_max segments per blade (eq. 4)
  double plantLodM = 4.0;             // eq. 4's distance unit
  bool noPlantShadows = false;
  double plantShadowM = 30.0;         // planar shadows within it (render::PlantDrawOptions)
  std::string occlusionCulling = "on";  // on | off: Hi-Z culling of seed triangles the terrain hides
  std::string bladePath = "auto";  // auto | tessellation | compute | mesh (render::BladePath)
};

// Adds the options to `cmd`; `withMode` adds --streaming (record only: fly is always realtime).
void addStreamingOptions(CLI::App& cmd, StreamingCli& o, bool withMode);

// Checks the values (one message naming the option) and fills the scene options.
Status applyStreamingOptions(const StreamingCli& o, scene::StreamingMode defaultMode, scene::SceneOptions& scene);

}  // namespace vegstream::app
