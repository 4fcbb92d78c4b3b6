// The HUD as plain overlay data: ImGui's layout becomes vertices, indices and clipped commands
// inside the display, with the font atlas as the one texture; absent counts print as a dash.

#include <gtest/gtest.h>

#include "app/hud.h"
#include "app/imgui_overlay.h"

namespace vegstream::app {
namespace {

HudState sampleState() {
  HudState s;
  s.datasetName = "test";
  s.deviceName = "llvmpipe";
  s.fps = 59.9;
  s.frameTimesMs = {16.0f, 17.0f, 16.5f};
  render::GpuTimings g;
  g.frameMs = 3.0;
  g.perPassMeaningful = false;
  s.gpu = g;
  s.terrainTriangles = 123456;
  s.streaming = "whole dataset resident";
  s.showHelp = true;
  return s;
}

TEST(InteractiveHud, OverlayDataIsConsistent) {
  ImGuiOverlay overlay;
  for (int frame = 0; frame < 2; ++frame) {  // ImGui sizes auto-resizing windows on the 2nd frame
    overlay.begin(640.0f, 360.0f, 1.0 / 60.0);
    drawHud(sampleState());
    const render::OverlayDrawData& d = overlay.end();
    EXPECT_FLOAT_EQ(d.width, 640.0f);
    EXPECT_FLOAT_EQ(d.height, 360.0f);
    ASSERT_TRUE(d.texture);
    EXPECT_GT(d.texture->id, 0u);
    EXPECT_EQ(d.texture->rgba.size(), size_t{d.texture->width} * d.texture->height * 4);
    if (frame == 0) continue;
    ASSERT_FALSE(d.commands.empty());
    ASSERT_FALSE(d.vertices.empty());
    for (const render::OverlayCommand& c : d.commands) {
      EXPECT_LE(size_t{c.firstIndex} + c.indexCount, d.indices.size());
      EXPECT_EQ(c.indexCount % 3, 0u);
      EXPECT_GE(c.vertexOffset, 0);
      EXPECT_LE(c.clipX0, c.clipX1);
      EXPECT_LE(c.clipY0, c.clipY1);
      for (uint32_t i = c.firstIndex; i < c.firstIndex + c.indexCount; ++i)
        ASSERT_LT(size_t(c.vertexOffset) + d.indices[i], d.vertices.size());
    }
  }
}

TEST(InteractiveHud, Formatting) {
  EXPECT_EQ(formatCount(std::nullopt), "\xE2\x80\x94");
  EXPECT_EQ(formatCount(std::nullopt, "--"), "--");
  EXPECT_EQ(formatCount(uint64_t{0}), "0");
  EXPECT_EQ(formatCount(uint64_t{1234567}), "1,234,567");
  EXPECT_EQ(formatBytes(999), "999 B");
  EXPECT_EQ(formatBytes(1'500'000), "1.50 MB");
}

}  // namespace
}  // namespace vegstream::app
