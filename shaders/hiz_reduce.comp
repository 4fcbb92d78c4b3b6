#version 450
// One Hi-Z level from the level below it (render/hiz_pass.h): each texel keeps the FARTHEST
// (reverse-Z: smallest) depth of its 2 × 2 children. Level sizes round up (ceil), so a texel
// at the right or bottom edge may have only one or two children: only those that exist count,
// and a texel of level l covers exactly the pixels [i·2^(l+1), (i+1)·2^(l+1)) on screen.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, std430) buffer Hiz { float hiz[]; };
layout(push_constant) uniform Push { uint srcOffset, srcW, srcH, dstOffset, dstW, dstH; } pc;

void main() {
  uvec2 t = gl_GlobalInvocationID.xy;
  if (t.x >= pc.dstW || t.y >= pc.dstH) return;
  float farthest = 1.0;
  for (uint dy = 0u; dy < 2u; ++dy)
    for (uint dx = 0u; dx < 2u; ++dx) {
      uvec2 c = 2u * t + uvec2(dx, dy);
      if (c.x < pc.srcW && c.y < pc.srcH) farthest = min(farthest, hiz[pc.srcOffset + c.y * pc.srcW + c.x]);
    }
  hiz[pc.dstOffset + t.y * pc.dstW + t.x] = farthest;
}
