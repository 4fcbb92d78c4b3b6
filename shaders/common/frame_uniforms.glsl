// Per-frame uniforms shared by every pass. Mirrors render/frame_uniforms.h (std140; the C++
// side checks offsets with static_assert). Positions are in the local ENU frame, relative to
// the camera: the camera sits at the origin, so view matrices hold rotation only.
layout(set = 0, binding = 0, std140) uniform FrameUniforms {
  mat4 viewProj;      // projection * rotation-only view (reverse-Z: near → 1, far → 0)
  mat4 invViewProj;   // its inverse, for sky rays
  vec4 sunDirection;  // xyz: unit vector towards the sun; w: unused
  vec4 atmosphere;    // x: the camera's radius from the planet's centre (km), y: the aerial-perspective volume's far distance (km) (atmosphere.glsl)
  vec4 viewport;      // xy: size in pixels, zw: 1 / size
  vec4 detail;        // xyz: camera position modulo the detail period (m, world-anchored tiling), w: detail strength 0 … 1
  mat4 shadowMatrices[3];  // camera-relative → each sun shadow cascade's clip space (render/shadow_cascades.h)
  vec4 shadowSplits;       // xyz: each cascade's far view distance (m), w: 1 when the shadow map holds this frame's casters
  vec4 shadowTexel;        // xyz: each cascade's texel size (m), w: the cascades drawn this frame (bit c; render/shadow_refresh.h)
  vec4 terrainDepth;       // x: 1 when the terrain was rasterised in compute (its depth samples, binding 5, go into the depth attachment: terrain_depth.frag), y: samples per pixel, z: 1 when the Hi-Z pyramid (set 0 binding 6) holds this frame's terrain before the trees (hiz_occlusion.glsl)
  vec4 outputs;            // x: 1 in an AOV frame (aov.glsl: vegetation coverage and species instead of colour)
} frame;
