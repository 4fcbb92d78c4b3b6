// The seeding stage's figures (frame_figures.h): the time making the seed triangles ready for
// the classify pass (the binning is in cpu_record_submit_ms; what the pass made of them is the
// render stage's).

#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

void declareSeedingFigures(FrameFigures& out, const FigureLayout&) {
  out.push_back(
      {FigureSection::CpuStages, {"cpu_seeding_ms", 6, "ms"}, [](const FrameRecord& r) { return r.scene.seedingMs; }});
}

}  // namespace vegstream::scene
