#version 450
#extension GL_GOOGLE_include_directive : require
// Classification markers (until the species pipelines of issue 8): one upright triangle per plant
// of each classified group, as tall and wide as the plant, in its species' marker colour. The
// plant's root and size come from the same seeding code as the CPU reference
// (vegetation/plant_seeding.cpp); a group of fewer seeds than the cluster size leaves its extra
// triangles degenerate.
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"

layout(set = 1, binding = 0, std140) uniform SpeciesBlock {
  Species species[kMaxSpecies];
  uvec4 speciesCount;
} catalog;
layout(set = 1, binding = 1, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 1, binding = 2, std430) readonly buffer Records { PlantCluster records[]; };
layout(push_constant) uniform Push { uint species; uint speciesCapacity; } pc;

layout(location = 0) out vec3 outColour;

void main() {
  PlantCluster g = records[pc.species * pc.speciesCapacity + uint(gl_InstanceIndex)];
  uint seed = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  outColour = vec3(0.0);
  if (seed >= g.seedCount) {
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  seed += g.firstSeed;
  SeedTriangle t = triangles[g.triangle];
  uvec2 key = uvec2(t.keyLo, t.keyHi);
  vec2 r = seedPoint(key, g.cluster, seed);
  vec3 root = t.v0.xyz + r.x * (t.v1.xyz - t.v0.xyz) + r.y * (t.v2.xyz - t.v0.xyz);
  Species sp = catalog.species[g.species];
  uvec2 hs = philoxDraw(key, g.cluster, kSlotHeightStiffness + seed);
  uvec2 ow = philoxDraw(key, g.cluster, kSlotOrientationWidth + seed);
  float height = mix(sp.heightStiffness.x, sp.heightStiffness.y, philoxU01(hs.x)) * (0.6 + 0.4 * g.sPrime) * g.fade;
  // Wider than the plant itself, so that markers of thin blades show at a distance.
  float width = max(mix(sp.widthColour.x, sp.widthColour.y, philoxU01(ow.y)) * 3.0, 0.3 * height);
  // Facing the camera: the base spans the horizontal perpendicular to the view ray.
  vec3 side = normalize(cross(vec3(0.0, 0.0, 1.0), root) + vec3(1e-6, 0.0, 0.0));
  vec3 p = corner == 0u ? root - 0.5 * width * side : (corner == 1u ? root + 0.5 * width * side : root + vec3(0.0, 0.0, height));
  outColour = sp.marker.rgb * (corner == 2u ? 1.0 : 0.6);
  gl_Position = frame.viewProj * vec4(p, 1.0);
}
