#pragma once
// The number of frame slots: how many frames may be in flight on the GPU at once. Every
// per-frame resource — the renderer's command buffers, fences, uniforms, timers and read-back
// buffers, and the per-slot buffers of the HUD, terrain, classify and plant passes — has this
// many copies, indexed by frame index % kFramesInFlight. Three slots let the CPU prepare two
// frames while the GPU draws a third (scene/frame_driver.h), so a frame's wall time comes close
// to max(CPU, GPU) instead of their sum. Plain data: scene/ and app/ read it too.

namespace vegstream::render {

inline constexpr int kFramesInFlight = 3;

}  // namespace vegstream::render
