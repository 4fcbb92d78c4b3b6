#pragma once
// A 2D overlay (the HUD) as plain data: textured, coloured triangles in pixels with per-command
// clip rectangles, plus the one RGBA texture they sample (a font atlas). The app builds it
// (with Dear ImGui) and hands it to the renderer through FrameRequest::overlay; render/ draws
// it with its own pipeline (hud_pass.h), so neither side sees the other's types.

#include <cstdint>
#include <memory>
#include <vector>

namespace vegstream::render {

// 20 bytes, the layout of ImDrawVert: position in pixels (origin top-left), texture
// coordinate, colour as RGBA8 (R in the lowest byte), sRGB-encoded.
struct OverlayVertex {
  float x = 0.0f, y = 0.0f;
  float u = 0.0f, v = 0.0f;
  uint32_t rgba = 0;
};
static_assert(sizeof(OverlayVertex) == 20, "must match shaders/hud.vert's attributes");

// One indexed draw: indices [firstIndex, firstIndex + indexCount) added to vertexOffset,
// clipped to the pixel rectangle [clipX0, clipX1) × [clipY0, clipY1).
struct OverlayCommand {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  int32_t vertexOffset = 0;
  float clipX0 = 0.0f, clipY0 = 0.0f, clipX1 = 0.0f, clipY1 = 0.0f;
};

// An RGBA8 image (straight alpha, sRGB colour). `id` changes whenever the pixels change, so the
// renderer uploads it once per id.
struct OverlayImage {
  uint64_t id = 0;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

struct OverlayDrawData {
  // The pixel size the overlay was laid out for; it is scaled to the render target's size.
  float width = 0.0f, height = 0.0f;
  std::vector<OverlayVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<OverlayCommand> commands;
  std::shared_ptr<const OverlayImage> texture;  // sampled by every command; required when commands exist
};

}  // namespace vegstream::render
