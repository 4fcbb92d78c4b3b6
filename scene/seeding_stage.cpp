// The seeding stage (seeding_stage.h): its run and its figures — the time making the seed
// triangles ready for the classify pass.

#include "scene/seeding_stage.h"

#include "core/stopwatch.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

void SeedingStage::run(FrameContext& context) {
  if (!options_.plants) return;
  Stopwatch stage;
  seedTrianglesForGpu(terrain_.seedTriangles(), context.camera.position, seeds_);
  context.figures.seedingMs = stage.elapsedMs();
  context.vegetation = {seeds_, options_.clusterSize, options_.plantStyle, options_.plantDraw,
                        options_.occlusionCulling};
  context.request.vegetation = &context.vegetation;
  context.figures.seedTrianglesClassified = seeds_.size();
}

void SeedingStage::declareFigures(FrameFigures& out, const FigureLayout&) {
  out.push_back(
      {FigureSection::CpuStages, {"cpu_seeding_ms", 6, "ms"}, [](const FrameRecord& r) { return r.scene.seedingMs; }});
}

}  // namespace vegstream::scene
