#include "app/window_input.h"

#include <GLFW/glfw3.h>

namespace vegstream::app {

WindowInput::WindowInput(GLFWwindow* window) : window_(window) {
  glfwSetWindowUserPointer(window_, this);
  glfwSetScrollCallback(window_, &WindowInput::onScroll);
}

WindowInput::~WindowInput() {
  glfwSetScrollCallback(window_, nullptr);
  glfwSetWindowUserPointer(window_, nullptr);
  glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
}

void WindowInput::onScroll(GLFWwindow* window, double /*dx*/, double dy) {
  if (auto* self = static_cast<WindowInput*>(glfwGetWindowUserPointer(window))) self->wheel_ += dy;
}

bool WindowInput::pressedOnce(int key) {
  const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
  bool& was = wasDown_[key];
  const bool edge = down && !was;
  was = down;
  return edge;
}

FlyInput WindowInput::poll(WindowActions& a) {
  auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS; };
  a = {};
  a.quit = down(GLFW_KEY_ESCAPE);
  a.toggleFollow = pressedOnce(GLFW_KEY_F);
  a.screenshot = pressedOnce(GLFW_KEY_P);
  a.toggleRecord = pressedOnce(GLFW_KEY_R);
  a.toggleHelp = pressedOnce(GLFW_KEY_F1);
  a.toggleHud = pressedOnce(GLFW_KEY_H);
  a.cycleCollider = pressedOnce(GLFW_KEY_C);
  // GLFW names keys by their place on a US keyboard, so these are the same four keys right of
  // L and P on any layout.
  auto steps = [&](int raise, int lower) { return (pressedOnce(raise) ? 1 : 0) - (pressedOnce(lower) ? 1 : 0); };
  a.wind.speedSteps = steps(GLFW_KEY_RIGHT_BRACKET, GLFW_KEY_LEFT_BRACKET);
  a.wind.directionSteps = steps(GLFW_KEY_PERIOD, GLFW_KEY_COMMA);
  a.wind.gustinessSteps = steps(GLFW_KEY_APOSTROPHE, GLFW_KEY_SEMICOLON);
  a.time.steps = steps(GLFW_KEY_EQUAL, GLFW_KEY_MINUS);

  FlyInput in;
  in.forward = (down(GLFW_KEY_W) ? 1.0 : 0.0) - (down(GLFW_KEY_S) ? 1.0 : 0.0);
  in.right = (down(GLFW_KEY_D) ? 1.0 : 0.0) - (down(GLFW_KEY_A) ? 1.0 : 0.0);
  in.up = (down(GLFW_KEY_E) ? 1.0 : 0.0) - (down(GLFW_KEY_Q) ? 1.0 : 0.0);
  in.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
  a.wind.coarse = in.fast;
  a.time.coarse = in.fast;
  in.wheelSteps = wheel_;
  wheel_ = 0.0;

  const bool look = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  if (look && !looking_) {
    glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_DISABLED);
    glfwGetCursorPos(window_, &x, &y);  // disabling may move the virtual cursor
  } else if (!look && looking_) {
    glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
  } else if (look) {
    in.lookDxPx = x - lastX_;
    in.lookDyPx = y - lastY_;
  }
  looking_ = look;
  lastX_ = x;
  lastY_ = y;

  // The HUD is laid out in framebuffer pixels; the cursor comes in window coordinates (they
  // differ on HiDPI displays).
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  pointer_ = {};
  if (!look && ww > 0 && wh > 0) {
    pointer_.present = true;
    pointer_.x = static_cast<float>(x * fw / ww);
    pointer_.y = static_cast<float>(y * fh / wh);
    pointer_.leftDown = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  }
  return in;
}

}  // namespace vegstream::app
