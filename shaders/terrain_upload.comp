#version 450
// The terrain's vertex uploads (render/terrain_geometry_buffers.h): one workgroup per upload
// copies its vertices from the frame slot's staging buffer into their range of the vertex pool.
// One dispatch instead of one copy region per chunk: on the H100 each region of a
// vkCmdCopyBuffer cost about 2.4 µs of GPU time, a millisecond a frame on benchmark-30s.
layout(local_size_x = 64) in;

const uint kVertexFloats = 9u;  // terrain::TerrainVertex, 36 bytes

layout(std430, set = 0, binding = 0) readonly buffer Staged { float staged[]; };
// x: first staged vertex, y: first pool vertex, z: vertices
layout(std430, set = 0, binding = 1) readonly buffer Uploads { uvec4 uploads[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Pool { float pool[]; };
layout(push_constant) uniform UploadPush {
  uint count;  // uploads
  uint perRow; // workgroups along x
} push;

void main() {
  uint index = gl_WorkGroupID.y * push.perRow + gl_WorkGroupID.x;
  if (index >= push.count) return;
  uvec4 u = uploads[index];
  uint from = u.x * kVertexFloats, to = u.y * kVertexFloats, n = u.z * kVertexFloats;
  for (uint i = gl_LocalInvocationID.x; i < n; i += gl_WorkGroupSize.x) pool[to + i] = staged[from + i];
}
