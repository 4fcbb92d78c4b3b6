// A still's sidecar JSON (frame_sidecar.h).

#include "scene/frame_sidecar.h"


#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "render/png_writer.h"

namespace vegstream::scene {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json countsOf(const FrameRecord& f) {
  const auto& v = f.vegetation;
  const auto& t = f.trees;
  json trees = nullptr;
  if (t && t->gpuCounts) trees = {{"full", t->full}, {"reduced", t->reduced}, {"impostor", t->impostor}};
  return {{"terrain_triangles", f.terrainTriangles},
          {"seed_triangles", v ? json(v->seedTriangles) : json(nullptr)},
          {"plants", v && v->gpuCounts ? json(v->plantsTotal) : json(nullptr)},
          {"trees", trees}};
}

}  // namespace

fs::path sidecarPathFor(const fs::path& png) {
  fs::path out = png;
  return out.replace_extension(".json");
}

std::string frameSidecarJson(const FrameRecord& f, uint32_t width, uint32_t height, const Scene& scene) {
  const flight::FlightSample& p = f.pose;
  const SunClock& clock = scene.sunClock();
  const json j = {{"pose",
                   {{"lat", p.position.latDeg},
                    {"lon", p.position.lonDeg},
                    {"alt_m_msl", p.position.heightM},
                    {"alt_m_above_ground", p.heightAboveGroundM},
                    {"heading_deg", p.headingDeg},
                    {"pitch_deg", p.pitchDeg}}},
                  {"vertical_fov_deg", f.verticalFovDeg},
                  {"datetime", geo::formatIsoDateTime(f.datetime)},
                  {"sun",
                   {{"azimuth_deg", f.sun.azimuthDeg},
                    {"elevation_deg", f.sun.elevationDeg},
                    {"lat", clock.latDeg},
                    {"lon", clock.lonDeg}}},
                  {"exposure_ev", f.exposureEv},
                  {"exposure_mode", scene.options().exposureEv ? "fixed" : "automatic"},
                  {"size", {{"width", width}, {"height", height}}},
                  {"counts", countsOf(f)}};
  return j.dump(2) + "\n";
}

Status writeFrameWithSidecar(const fs::path& png, const render::ColorImage& image, const std::string& sidecarJson) {
  auto bytes = render::encodePng(image, png);
  if (!bytes) return bytes.error();
  auto stagedPng = StagedFile::stage(png, *bytes);
  if (!stagedPng) return stagedPng.error();
  const std::span<const uint8_t> text(reinterpret_cast<const uint8_t*>(sidecarJson.data()), sidecarJson.size());
  auto stagedSidecar = StagedFile::stage(sidecarPathFor(png), text);
  if (!stagedSidecar) return stagedSidecar.error();
  if (Status s = stagedPng->commit(); !s) return s;
  return stagedSidecar->commit();
}

}  // namespace vegstream::scene
