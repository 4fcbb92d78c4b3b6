#pragma once
// A Dear ImGui context that produces plain overlay draw data (render/overlay_types.h) instead
// of talking to a graphics API: the app lays out the HUD with ImGui between begin() and end(),
// and the renderer draws the result with its own HUD pass. ImGui gets the pointer (position and
// left button) for the HUD's sliders, never the keyboard (the fly camera and the window's keys own
// it), and no imgui.ini is written.

#include <memory>

#include "render/overlay_types.h"

struct ImGuiContext;

namespace vegstream::app {

// The mouse as ImGui sees it, in the overlay's pixels (framebuffer pixels, not window
// coordinates, where they differ). Absent while the right button turns the camera: the cursor is
// captured then and must not drag a slider.
struct OverlayPointer {
  bool present = false;
  float x = 0.0f, y = 0.0f;
  bool leftDown = false;
};

class ImGuiOverlay {
 public:
  ImGuiOverlay();
  ~ImGuiOverlay();
  ImGuiOverlay(const ImGuiOverlay&) = delete;
  ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;

  // Starts an ImGui frame laid out for width × height pixels; dtS feeds ImGui's timers (and its
  // click detection), `pointer` its mouse.
  void begin(float width, float height, double dtS, const OverlayPointer& pointer = {});
  // Ends the frame and returns its draw data (valid until the next end()).
  const render::OverlayDrawData& end();

 private:
  ImGuiContext* context_ = nullptr;
  std::shared_ptr<render::OverlayImage> atlas_;
  render::OverlayDrawData data_;
};

}  // namespace vegstream::app
