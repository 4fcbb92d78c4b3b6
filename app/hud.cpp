#include "app/hud.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "app/wind_controls.h"

namespace vegstream::app {

std::string formatBytes(uint64_t bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1000.0 && u < 4) {
    v /= 1000.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), u == 0 ? "%.0f %s" : "%.2f %s", v, units[u]);
  return buf;
}

std::string formatCount(const std::optional<uint64_t>& count, const char* absent) {
  if (!count) return absent;  // not produced yet
  std::string digits = std::to_string(*count), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

namespace {
void drawGpu(const HudState& s) {
  if (s.cpuFrameMs) {
    if (s.cpuSimulationMs)
      ImGui::Text("CPU frame %.2f ms  (simulation %.2f ms)", *s.cpuFrameMs, *s.cpuSimulationMs);
    else
      ImGui::Text("CPU frame %.2f ms", *s.cpuFrameMs);
  }
  if (!s.gpu) {
    ImGui::TextUnformatted("GPU: waiting for the first frame");
    return;
  }
  const render::GpuTimings& g = *s.gpu;
  if (g.perPassMeaningful) {
    ImGui::Text("GPU frame %.2f ms", g.frameMs);
    for (const render::PassTime& p : g.passes) ImGui::Text("  %-10s %6.2f ms", p.pass.c_str(), p.ms);
  } else {
    ImGui::Text("GPU frame %.2f ms", g.frameMs);
    ImGui::TextDisabled("  (%s is a CPU rasteriser:", s.deviceName.c_str());
    ImGui::TextDisabled("   per-pass times are not meaningful)");
  }
}

void drawHelp() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::Begin("Controls (F1 closes)", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings);
  const char* lines[][2] = {
      {"Right mouse button (hold)", "look around"},
      {"W / S", "fly forward / back along the view"},
      {"A / D", "strafe left / right"},
      {"Q / E", "down / up (height above ground when following)"},
      {"Mouse wheel", "speed x1.25 per notch"},
      {"Shift (hold)", "5x faster"},
      {"F", "follow terrain on / off"},
      {"P", "screenshot (PNG)"},
      {"R", "start / stop recording a flight path (JSON)"},
      {"] / [", "wind speed +/- 1 m/s (with Shift: 10 m/s)"},
      {". / ,", "wind direction +/- 15 degrees (where it comes from)"},
      {"' / ;", "gustiness +/- 0.1"},
      {"= / -", "time of day +/- 30 min (with Shift: 3 h)"},
      {"Left mouse on the HUD", "drag the wind and time-of-day sliders"},
      {"C", "camera collider: walking / driving / off"},
      {"H", "hide / show the HUD"},
      {"F1", "this help"},
      {"Esc", "quit"},
  };
  if (ImGui::BeginTable("keys", 2)) {
    for (const auto& l : lines) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(l[0]);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(l[1]);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

// The wind (with sliders for the same values as the keys) and the collider that follows the
// camera. Returns the edited wind when a slider moved.
std::optional<simulation::WindOptions> drawSimulation(const HudState& s) {
  if (!s.simulationOn) {
    ImGui::TextDisabled("simulation off: nothing moves");
    return std::nullopt;
  }
  ImGui::Text("wind %s", describeWind(s.wind).c_str());
  simulation::WindOptions w = s.wind;
  const double speedMin = 0.0, speedMax = simulation::kMaxWindSpeedMps, dirMin = 0.0, dirMax = 360.0, gustMin = 0.0,
               gustMax = 1.0;
  w.directionDeg = std::fmod(std::fmod(w.directionDeg, 360.0) + 360.0, 360.0);  // the slider's range
  bool changed = false;
  ImGui::PushItemWidth(170.0f);
  changed |= ImGui::SliderScalar("speed (m/s)", ImGuiDataType_Double, &w.speedMps, &speedMin, &speedMax, "%.1f");
  changed |= ImGui::SliderScalar("from (deg)", ImGuiDataType_Double, &w.directionDeg, &dirMin, &dirMax, "%.0f");
  changed |= ImGui::SliderScalar("gustiness", ImGuiDataType_Double, &w.gustiness, &gustMin, &gustMax, "%.2f");
  ImGui::PopItemWidth();
  ImGui::Text("camera collider: %s  (C)", s.cameraCollider.c_str());
  if (s.pathColliders > 0 || s.pathWindSources > 0)
    ImGui::Text("path: %zu colliders, %zu wind sources", s.pathColliders, s.pathWindSources);
  if (!changed) return std::nullopt;
  return clampWind(w);
}

// The sun's line and the time-of-day slider; the new local hours when it moved.
std::optional<double> drawSun(const HudState& s) {
  ImGui::TextUnformatted(s.sun.c_str());
  double hours = s.timeOfDayH;
  const double lo = 0.0, hi = 24.0;
  ImGui::PushItemWidth(170.0f);
  const bool changed = ImGui::SliderScalar("time of day (h)", ImGuiDataType_Double, &hours, &lo, &hi, "%.2f");
  ImGui::PopItemWidth();
  if (!changed) return std::nullopt;
  return hours;
}
}  // namespace

HudEdits drawHud(const HudState& s) {
  HudEdits edits;
  ImGui::SetNextWindowPos(ImVec2(6.0f, 6.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.72f);
  // Takes the mouse for its sliders, but never moves, scrolls or collapses (ImGui gets no wheel).
  ImGui::Begin("vegstream", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::Text("%s  |  %s", s.datasetName.c_str(), s.deviceName.c_str());
  const float lastMs = s.frameTimesMs.empty() ? 0.0f : s.frameTimesMs.back();
  ImGui::Text("%.1f FPS  (%.2f ms)", s.fps, static_cast<double>(lastMs));
  if (!s.frameTimesMs.empty()) {
    const float maxMs = *std::max_element(s.frameTimesMs.begin(), s.frameTimesMs.end());
    char label[32];
    std::snprintf(label, sizeof(label), "max %.1f ms", static_cast<double>(maxMs));
    ImGui::PlotLines("##frametimes", s.frameTimesMs.data(), static_cast<int>(s.frameTimesMs.size()), 0, label, 0.0f,
                     std::max(maxMs * 1.1f, 1.0f), ImVec2(220.0f, 40.0f));
  }
  drawGpu(s);
  ImGui::Separator();
  ImGui::Text("terrain triangles  %s", formatCount(s.terrainTriangles).c_str());
  const char* absent = ImGui::GetFont()->FindGlyphNoFallback(0x2014) ? "\xE2\x80\x94" : "--";
  ImGui::Text("seed triangles     %s", formatCount(s.seedTriangles, absent).c_str());
  ImGui::Text("plants             %s", formatCount(s.plants, absent).c_str());
  ImGui::Text("plant triangles    %s", formatCount(s.plantTriangles, absent).c_str());
  ImGui::Separator();
  ImGui::TextUnformatted(s.streaming.c_str());
  ImGui::Text("resident: CPU %s, GPU %s", formatBytes(s.cpuBytes).c_str(), formatBytes(s.gpuBytes).c_str());
  ImGui::Separator();
  ImGui::Text("lat %.6f  lon %.6f", s.latDeg, s.lonDeg);
  ImGui::Text("alt %.1f m MSL  (%.1f m above ground)", s.altMslM, s.aglM);
  ImGui::Text("heading %.1f  pitch %.1f  speed %.0f m/s", s.headingDeg, s.pitchDeg, s.speedMps);
  ImGui::Text("follow terrain: %s", s.followTerrain ? "on" : "off");
  ImGui::Separator();
  edits.wind = drawSimulation(s);
  ImGui::Separator();
  edits.timeOfDayH = drawSun(s);
  ImGui::Separator();
  if (s.recording)
    ImGui::TextColored(ImVec4(1.0f, 0.3f, 0.3f, 1.0f), "REC %.1f s, %zu keyframes", s.recordingS, s.recordedKeyframes);
  if (!s.message.empty()) ImGui::TextUnformatted(s.message.c_str());
  ImGui::TextDisabled("F1: help");
  ImGui::End();
  if (s.showHelp) drawHelp();
  return edits;
}

}  // namespace vegstream::app
