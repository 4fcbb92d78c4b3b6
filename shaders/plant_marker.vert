#version 450
#extension GL_GOOGLE_include_directive : require
// Classification markers (kinds without a species pipeline, and PlantStyle::Markers): one upright
// triangle per plant of each classified group, as tall as the plant, in its species' marker
// colour. Root and size come from the same code as the species pipelines
// (shaders/common/plant_params.glsl, the twin of vegetation/plant_seeding.cpp); a group of fewer
// seeds than the cluster size leaves its extra triangles degenerate.
#include "frame_uniforms.glsl"
#include "philox.glsl"
#include "seeding.glsl"
#include "classify_layout.glsl"
#include "simulation_fields.glsl"

layout(set = 1, binding = 0, std140) uniform SpeciesBlock {
  Species species[kMaxSpecies];
  uvec4 speciesCount;
} catalog;
layout(set = 1, binding = 1, std430) readonly buffer Triangles { SeedTriangle triangles[]; };
layout(set = 1, binding = 2, std430) readonly buffer Records { PlantCluster records[]; };
layout(push_constant) uniform Push { uint species; uint speciesCapacity; } pc;

#include "plant_params.glsl"

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
  PlantParams plant = plantParams(g, triangles[g.triangle], seed);
  vec3 root = plant.root;
  Species sp = catalog.species[g.species];
  float height = plant.height;
  // Wider than the plant itself, so that markers of thin blades show at a distance.
  float width = max(plant.width * 3.0, 0.3 * height);
  // Facing the camera: the base spans the horizontal perpendicular to the view ray.
  vec3 side = normalize(cross(vec3(0.0, 0.0, 1.0), root) + vec3(1e-6, 0.0, 0.0));
  vec3 p = corner == 0u ? root - 0.5 * width * side : (corner == 1u ? root + 0.5 * width * side : root + vec3(0.0, 0.0, height));
  outColour = sp.marker.rgb * (corner == 2u ? 1.0 : 0.6);
  gl_Position = frame.viewProj * vec4(p, 1.0);
}
