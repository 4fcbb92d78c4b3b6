#pragma once
// The sidecar F.json beside a still F.png (issue 39: `snapshot --out F.png`, and each frame PNG
// a recording saves): what the image shows, for tools that measure it — the pose, the vertical
// field of view, the date-time and the sun (azimuth clockwise from north, elevation with
// refraction), the exposure the frame was tone-mapped with, the image size and the frame's counts.
// Keys (app/README.md "Stills"): pose {lat, lon, alt_m_msl, alt_m_above_ground, heading_deg,
// pitch_deg}, vertical_fov_deg, datetime, sun {azimuth_deg, elevation_deg, lat, lon (where it is
// seen from: the dataset's centre)}, exposure_ev,
// exposure_mode (fixed | automatic), size {width, height}, counts {terrain_triangles,
// seed_triangles, plants, trees {full, reduced, impostor}} — a count the frame did not produce
// (no plants, not read back on this device) is null.

#include <filesystem>
#include <string>

#include "core/result.h"
#include "render/frame_types.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

// F.json for F.png.
std::filesystem::path sidecarPathFor(const std::filesystem::path& png);

// The sidecar's text for a frame of width × height that `scene` drew.
std::string frameSidecarJson(const FrameRecord& frame, uint32_t width, uint32_t height, const Scene& scene);

// Writes `png` and its sidecar: both are staged (written, checked, fsynced under temporary
// names, core/atomic_file.h) before either is renamed into place, so a failure while writing
// (a full disk) leaves an earlier pair exactly as it was. Only a failed rename between the two
// (or a kill there) can leave a new PNG beside an older sidecar.
Status writeFrameWithSidecar(const std::filesystem::path& png, const render::ColorImage& image,
                             const std::string& sidecarJson);

}  // namespace vegstream::scene
