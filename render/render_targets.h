#pragma once
// Offscreen colour + depth targets. The scene is drawn in linear HDR (packed floats). With MSAA
// (samples > 1) the multisampled attachments are resolved at the end of the frame's last
// rendering scope — colour by averaging, depth by taking sample 0 — into single-sample images;
// with samples == 1 the attachments are those images themselves. The tone map
// (render/tonemap_pass.h) turns the resolved HDR colour into the sRGB display target, which is
// what is copied, presented or read back.

#include <optional>

#include "render/gpu_resources.h"

namespace vegstream::render {

// The scene's colour: linear HDR radiance (render/tonemap_pass.h's units); MSAA resolve averages
// it in linear light. Packed unsigned floats (11, 11 and 10 bits: 6, 6 and 5 bits of mantissa,
// the range of half floats, no alpha, no negatives), stored from compute directly (the deferred
// terrain shade, as `r11f_g11f_b10f`): four bytes a sample, as the 8-bit target before HDR. With
// RGBA16F the 4× MSAA target was twice the bytes to clear, write and resolve: on the H100 at
// 1080p the orbit flight's GPU frame went from 2.16 to 2.39 ms (p50) with the HDR passes, 0.1 ms
// of it outside any pass (bench/README.md). The blue's 5 bits step 3 % in linear light, about 1
// % in sRGB: the sky's gradient, its smoothest colour, is stored dithered (terrain_shade.glsl).
constexpr VkFormat kColorFormat = VK_FORMAT_B10G11R11_UFLOAT_PACK32;
// The display target: tone-mapped, sRGB-encoded bytes (display-ready when read back). The tone
// map stores through a UNORM view (sRGB formats have no storage) and encodes sRGB itself.
constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kDisplayStorageFormat = VK_FORMAT_R8G8B8A8_UNORM;
// Reverse-Z float depth: near → 1, far → 0, for precision from 1 m to 100 km.
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// Deferred terrain shading: per sample, 1 + the index of the triangle it sees (0: none), its
// four bytes stored as UNORM: on the H200 a 4× MSAA R32_UINT target wrote samples at a quarter
// of RGBA8's rate (2.5 ms against 0.7 for the same triangles).
constexpr VkFormat kVisibilityFormat = VK_FORMAT_R8G8B8A8_UNORM;


class RenderTargets {
 public:
  // `deferredTerrain`: the terrain is shaded in compute: a storage view of the colour attachment,
  // and a visibility target unless `computeRaster` (the terrain is rasterised in compute too,
  // render/terrain_raster_pass.h: its depth is not in the depth attachment).
  RenderTargets(const Context& ctx, VkExtent2D extent, VkSampleCountFlagBits samples, bool deferredTerrain = false,
                bool computeRaster = false);

  VkExtent2D extent() const { return extent_; }
  VkSampleCountFlagBits samples() const { return samples_; }
  bool multisampled() const { return samples_ != VK_SAMPLE_COUNT_1_BIT; }

  const GpuImage& colorAttachment() const { return multisampled() ? colorMsaa_ : color_; }
  const GpuImage& depthAttachment() const { return multisampled() ? depthMsaa_ : depth_; }
  const GpuImage& color() const { return color_; }  // single-sample HDR, after resolve
  const GpuImage& display() const { return display_; }  // tone-mapped sRGB (TonemapPass)
  const GpuImage& depth() const { return depth_; }  // single-sample, after resolve

  bool deferredTerrain() const { return deferredTerrain_; }
  bool computeRaster() const { return deferredTerrain_ && visibility_.get() == VK_NULL_HANDLE; }
  const GpuImage& visibility() const { return visibility_; }  // attachment sample count
  // The colour attachment as a storage image (deferred terrain only).
  VkImageView colorStorageView() const { return colorAttachment().view.get(); }

  // Begins dynamic rendering into the colour and depth attachments, viewport and scissor over the
  // whole extent.
  // - Clear: the frame's first scope — every target (resolve targets too) starts undefined and
  //   is cleared.
  // - Keep: a later scope continues on what the previous scope stored (a barrier orders its
  //   writes first); the images are still in their attachment layouts.
  // - Shaded: the first scope after the deferred terrain — the colour attachment comes from the
  //   shade (GENERAL layout, written by compute), the depth from beginVisibility's scope (or,
  //   with the terrain rasterised in compute, from beginTerrainDepth's).
  // `resolve` (multisampled only): resolve into color() and depth() at the end — the frame's last
  // scope; otherwise the MSAA attachments are stored for the next one. `resolveDepth`: whether
  // depth() is resolved too (only a frame that reads its depth back needs it; on the H200 the
  // depth resolve cost about 0.15 ms a frame).
  enum class Load { Clear, Keep, Shaded };
  void beginRendering(VkCommandBuffer cmd, Load load = Load::Clear, bool resolve = true,
                      bool resolveDepth = true) const;

  // Deferred terrain: begins rendering into the visibility and depth attachments (no resolve).
  // Depth is cleared, the visibility target is not: the shade reads sky where depth is 0.
  void beginVisibility(VkCommandBuffer cmd) const;
  // After the visibility scope: the visibility and depth targets become readable (sampled) and
  // the colour attachment writable by compute (GENERAL). The shade returns the depth to its
  // attachment layout.
  void visibilityToShade(VkCommandBuffer cmd) const;
  // Opens a scope of the depth attachment alone, its contents discarded, or cleared to
  // `clearDepth` (the terrain rasterised in compute writes where something is depth-tested:
  // TerrainDepthHandover::record); the caller ends it.
  void beginTerrainDepth(VkCommandBuffer cmd, std::optional<float> clearDepth = std::nullopt) const;

 private:
  // Begins rendering over the whole extent into one colour and one depth attachment.
  void beginScope(VkCommandBuffer cmd, const VkRenderingAttachmentInfo& color,
                  const VkRenderingAttachmentInfo& depth) const;
  void setViewport(VkCommandBuffer cmd) const;

  VkExtent2D extent_;
  VkSampleCountFlagBits samples_;
  bool deferredTerrain_ = false;
  GpuImage colorMsaa_, depthMsaa_;
  GpuImage color_, depth_;
  GpuImage display_;
  GpuImage visibility_;
};

}  // namespace vegstream::render
