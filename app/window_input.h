#pragma once
// Reads the GLFW window's keyboard and mouse once per frame into FlyInput (fly_camera.h) plus
// the one-shot actions (key presses, not holds). Mouse-look works while the right button is
// held: the cursor is hidden and captured for that time, so the view can turn without limit.
// Otherwise the cursor and the left button go to the HUD (its wind sliders).

#include "app/fly_camera.h"
#include "app/imgui_overlay.h"
#include "app/time_of_day.h"
#include "app/wind_controls.h"

struct GLFWwindow;

namespace vegstream::app {

struct WindowActions {
  bool quit = false;          // Esc
  bool toggleFollow = false;  // F
  bool screenshot = false;    // P
  bool toggleRecord = false;  // R
  bool toggleHelp = false;    // F1
  bool toggleHud = false;     // H
  bool cycleCollider = false;  // C: camera collider off → walking → driving → off
  WindKeys wind;               // ] [ speed (Shift: ×10), . , direction, ' ; gustiness
  TimeKeys time;               // = - the time of day ±30 min (Shift: ±3 h)
};

class WindowInput {
 public:
  explicit WindowInput(GLFWwindow* window);  // installs a scroll callback (user pointer: this)
  ~WindowInput();
  WindowInput(const WindowInput&) = delete;
  WindowInput& operator=(const WindowInput&) = delete;

  // After glfwPollEvents: this frame's movement/look input and actions.
  FlyInput poll(WindowActions& actions);
  // The cursor for the HUD, as of the last poll (absent while looking around).
  const OverlayPointer& pointer() const { return pointer_; }

 private:
  static void onScroll(GLFWwindow* window, double dx, double dy);
  bool pressedOnce(int key);

  GLFWwindow* window_;
  double wheel_ = 0.0;
  bool looking_ = false;
  double lastX_ = 0.0, lastY_ = 0.0;
  bool wasDown_[512] = {};
  OverlayPointer pointer_;
};

}  // namespace vegstream::app
