// How the terrain is shaded (renderer.h TerrainShading): the names, and what a request becomes on
// a device — Auto resolved, or one message naming the option, the device and what it lacks.
#include <string>

#include "render/renderer.h"

namespace vegstream::render {

const char* terrainShadingName(TerrainShading shading) {
  switch (shading) {
    case TerrainShading::Auto: return "auto";
    case TerrainShading::Forward: return "forward";
    case TerrainShading::Deferred: return "deferred";
    case TerrainShading::Compute: return "compute";
  }
  return "?";
}

Result<TerrainShading> resolveTerrainShading(TerrainShading asked, const DeviceInfo& info, int msaa) {
  const bool canDefer = info.supportsDeferredTerrain(msaa);
  // Both shade in compute, storing into the colour target: one message names whichever was asked.
  if ((asked == TerrainShading::Deferred || asked == TerrainShading::Compute) && !canDefer)
    return makeError(ErrorKind::InvalidInput, std::string("--terrain-shading ") + terrainShadingName(asked) +
                                                  " is not possible on " + info.name + " at --msaa " +
                                                  std::to_string(msaa) +
                                                  ": it cannot store into a colour target of that many samples" +
                                                  " (storage images, shaderStorageImageMultisample)");
  const bool canRasterInCompute = info.supportsComputeTerrain(msaa);
  if (asked == TerrainShading::Compute && !canRasterInCompute)
    return makeError(ErrorKind::InvalidInput, "--terrain-shading compute is not possible on " + info.name +
                                                  " at --msaa " + std::to_string(msaa) +
                                                  ": it cannot run a fragment stage per sample (sampleRateShading)");
  if (asked == TerrainShading::Forward || !canDefer) return TerrainShading::Forward;
  if (asked == TerrainShading::Deferred) return TerrainShading::Deferred;
  if (asked == TerrainShading::Compute) return TerrainShading::Compute;
  // Auto: the terrain rasterised in compute on a GPU — where graphics units are few (the H200:
  // 2 of 66 TPCs) it is the fastest, measured side by side (render/README.md "The terrain
  // rasterised in compute") — and deferred on a CPU rasteriser (lavapipe), whose raster is
  // software either way.
  return !info.software && canRasterInCompute ? TerrainShading::Compute : TerrainShading::Deferred;
}

}  // namespace vegstream::render
