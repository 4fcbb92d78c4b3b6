// The pose of a frame turned into its views once (frame_context.h).

#include "scene/frame_context.h"

#include "core/stopwatch.h"
#include "scene/camera_views.h"

namespace vegstream::scene {

FrameContext::FrameContext(const geo::LocalFrame& frame, const flight::FlightSample& pose, double timeS,
                           std::span<const flight::FlightSample> ahead, double widthPx, double heightPx)
    : pose(pose), timeS(timeS) {
  Stopwatch watch;
  camera = cameraFor(frame, pose);
  selection = selectionViewFor(camera, widthPx, heightPx);
  eye = eyeViewFor(camera, widthPx, heightPx);
  this->ahead.reserve(ahead.size());
  for (const flight::FlightSample& s : ahead)
    this->ahead.push_back(selectionViewFor(cameraFor(frame, s), widthPx, heightPx));
  viewsMs = watch.elapsedMs();
}

}  // namespace vegstream::scene
