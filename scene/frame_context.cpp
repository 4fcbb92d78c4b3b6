// The pose of a frame turned into its views once (frame_context.h).

#include "scene/frame_context.h"

#include "core/stopwatch.h"
#include "scene/camera_views.h"
#include "scene/frame_input.h"

namespace vegstream::scene {

FrameContext::FrameContext(const geo::LocalFrame& frame, const flight::FlightSample& now, double t,
                           std::span<const flight::FlightSample> aheadPoses, double widthPx, double heightPx)
    : pose(now), timeS(t) {
  Stopwatch watch;
  camera = cameraFor(frame, now);
  selection = selectionViewFor(camera, widthPx, heightPx);
  eye = eyeViewFor(camera, widthPx, heightPx);
  ahead.reserve(aheadPoses.size());
  for (const flight::FlightSample& s : aheadPoses)
    ahead.push_back(selectionViewFor(cameraFor(frame, s), widthPx, heightPx));
  viewsMs = watch.elapsedMs();
}

bool FrameContext::repeatsLastFrame() const { return input && input->aov; }

}  // namespace vegstream::scene
