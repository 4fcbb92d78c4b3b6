#version 450
// The terrain's resident indices (render/terrain_index_pool.h): one workgroup per entry copies
// `count` indices from `source` to `target`, adding `add` to each. Two uses, one shader: a chunk's
// indices staged this frame into its range of the index pool (add: the chunk's first vertex in
// the vertex pool, so the pool holds them ready to draw), and each drawn chunk's indices from the
// pool into the frame's index buffer (add 0): a gather on the GPU where the frame thread used to
// rebase every index of every chunk, every frame.
layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Source { uint source[]; };
// x: first source index, y: first target index, z: count, w: added to each
layout(std430, set = 0, binding = 1) readonly buffer Entries { uvec4 entries[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Target { uint target[]; };
layout(push_constant) uniform CopyPush {
  uint first;   // this dispatch's first entry
  uint count;   // its entries
  uint perRow;  // workgroups along x
} push;

void main() {
  uint index = gl_WorkGroupID.y * push.perRow + gl_WorkGroupID.x;
  if (index >= push.count) return;
  uvec4 e = entries[push.first + index];
  for (uint i = gl_LocalInvocationID.x; i < e.z; i += gl_WorkGroupSize.x) target[e.y + i] = source[e.x + i] + e.w;
}
