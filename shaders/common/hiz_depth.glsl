// The first Hi-Z level from the frame's depth (render/hiz_pass.h): one texel per 2 × 2 pixel
// block, the FARTHEST depth of every sample in it. Reverse-Z (1 near, 0 far): farthest is the
// minimum. Taking every MSAA sample (not the resolve's sample 0) keeps the level conservative:
// a texel never claims a depth nearer than anything drawn under it. Included by hiz_depth.comp
// (single-sample), hiz_depth_ms.comp (HIZ_MSAA defined) and hiz_depth_buffer.comp (HIZ_BUFFER:
// the depth per pixel and sample of the terrain rasterised in compute, render/terrain_raster_pass.h).
#extension GL_EXT_samplerless_texture_functions : require
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef HIZ_BUFFER
layout(set = 0, binding = 0, std430) readonly buffer DepthSamples { float depthSamples[]; };
#elif defined(HIZ_MSAA)
layout(set = 0, binding = 0) uniform texture2DMS depthTex;
#else
layout(set = 0, binding = 0) uniform texture2D depthTex;
#endif
layout(set = 0, binding = 1, std430) writeonly buffer Hiz { float hiz[]; };

layout(push_constant) uniform Push {
  uint width, height;   // pixels of the depth target
  uint levelW, levelH;  // texels of level 0: ceil(width / 2), ceil(height / 2)
  uint samples;         // samples per pixel (1 without MSAA)
} pc;

void main() {
  uvec2 t = gl_GlobalInvocationID.xy;
  if (t.x >= pc.levelW || t.y >= pc.levelH) return;
  float farthest = 1.0;
  for (uint dy = 0u; dy < 2u; ++dy)
    for (uint dx = 0u; dx < 2u; ++dx) {
      uvec2 p = 2u * t + uvec2(dx, dy);
      if (p.x >= pc.width || p.y >= pc.height) continue;  // odd sizes: the block is cut by the edge
#ifdef HIZ_BUFFER
      for (uint s = 0u; s < pc.samples; ++s) farthest = min(farthest, depthSamples[(p.y * pc.width + p.x) * pc.samples + s]);
#elif defined(HIZ_MSAA)
      for (uint s = 0u; s < pc.samples; ++s) farthest = min(farthest, texelFetch(depthTex, ivec2(p), int(s)).r);
#else
      farthest = min(farthest, texelFetch(depthTex, ivec2(p), 0).r);
#endif
    }
  hiz[t.y * pc.levelW + t.x] = farthest;
}
