// The frame's own figures (frame_figures.h): its row, time and pose, the flight sampling and the
// CPU total, the recorder's times and the sun. The driver and the recorder fill them.

#include "flight/frame_columns.h"
#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

void declareFrameOwnFigures(FrameFigures& out, const FigureLayout&) {
  using S = FigureSection;
  using R = const FrameRecord&;
  namespace col = flight::column;
  out.push_back({S::Pose, {col::kFrame, 0, "frame"}, [](R r) { return static_cast<double>(r.row); }});
  out.push_back({S::Pose, {col::kTimeS, 6, "s"}, [](R r) { return r.timeS; }});
  out.push_back({S::Pose, {"lat", 9, "deg"}, [](R r) { return r.pose.position.latDeg; }});
  out.push_back({S::Pose, {"lon", 9, "deg"}, [](R r) { return r.pose.position.lonDeg; }});
  out.push_back({S::Pose, {"alt_msl_m", 3, "m"}, [](R r) { return r.pose.position.heightM; }});
  out.push_back({S::Pose, {"height_above_ground_m", 3, "m"}, [](R r) { return r.pose.heightAboveGroundM; }});
  out.push_back({S::Pose, {"heading_deg", 4, "deg"}, [](R r) { return r.pose.headingDeg; }});
  out.push_back({S::Pose, {"pitch_deg", 4, "deg"}, [](R r) { return r.pose.pitchDeg; }});
  out.push_back({S::CpuStages, {"cpu_flight_ms", 6, "ms"}, [](R r) { return r.flightMs; }});
  out.push_back({S::CpuFrame, {col::kCpuFrameMs, 6, "ms"}, [](R r) { return r.cpuMs(); }});
  out.push_back({S::Recorder, {col::kWallMs, 4, "ms"}, [](R r) { return r.wallMs; }});
  // Sub-microsecond: nanosecond digits.
  out.push_back({S::Recorder, {col::kRecorderMs, 6, "ms"}, [](R r) { return r.recorderMs; }});
  out.push_back({S::Recorder, {col::kPngMs, 4, "ms"}, [](R r) { return r.pngMs; }});
  // The sun (issue 39, sun_clock.h): seen from the dataset's centre at the frame's date-time.
  out.push_back({S::Sun, {"sun_azimuth_deg", 4, "deg"}, [](R r) { return r.sun.azimuthDeg; }});
  out.push_back({S::Sun, {"sun_elevation_deg", 4, "deg"}, [](R r) { return r.sun.elevationDeg; }});
}

}  // namespace vegstream::scene
