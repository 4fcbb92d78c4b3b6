#pragma once
// A Dear ImGui context that produces plain overlay draw data (render/overlay_types.h) instead
// of talking to a graphics API: the app lays out the HUD with ImGui between begin() and end(),
// and the renderer draws the result with its own HUD pass. Display-only: ImGui gets no mouse or
// keyboard input (the fly camera owns them), and no imgui.ini is written.

#include <memory>

#include "render/overlay_types.h"

struct ImGuiContext;

namespace vegstream::app {

class ImGuiOverlay {
 public:
  ImGuiOverlay();
  ~ImGuiOverlay();
  ImGuiOverlay(const ImGuiOverlay&) = delete;
  ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;

  // Starts an ImGui frame laid out for width × height pixels; dtS feeds ImGui's timers.
  void begin(float width, float height, double dtS);
  // Ends the frame and returns its draw data (valid until the next end()).
  const render::OverlayDrawData& end();

 private:
  ImGuiContext* context_ = nullptr;
  std::shared_ptr<render::OverlayImage> atlas_;
  render::OverlayDrawData data_;
};

}  // namespace vegstream::app
