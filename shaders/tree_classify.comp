#version 460
#extension GL_GOOGLE_include_directive : require
// Trees, issue 20: one thread per instance slot of the tree pool (render/tree_layout.h). Culls the
// tree against the view, picks its level of detail by distance in tree heights — full model,
// reduced model, octahedral impostor, then nothing (the terrain's own colour) — and appends it to
// its model's indirect draw at that level. Inside a switch's band it is appended at both levels
// with complementary dither thresholds (shaders/common/tree_layout.glsl treeKeepsPixel), so the
// two split the pixels and the switch is a cross-fade; past the horizon's band it dithers out.
// The wind at the tree comes from the shared simulation's field (simulation/shared/wind_field.glsl):
// the same gust crosses the meadow and then the forest. Every tree it keeps is also appended, once,
// to the shadow casters of each sun cascade whose box its sphere reaches (cast as its impostor
// turned to the sun, whatever its level), so a cascade draws only its own casters.
// mode 1 (push): clamp the draws' instance counts to their regions' capacity after the appends.
layout(local_size_x = 256) in;
#include "common/frame_uniforms.glsl"
#include "common/simulation_block.glsl"
#include "common/tree_layout.glsl"
#include "common/depth_tile_marks.glsl"
float treeTime() { return sim.clock.y + sim.clock.x * sim.clock.z; }

layout(set = 1, binding = 4, std430) readonly buffer PageCounts { uint pageCounts[]; };
layout(set = 1, binding = 5, std430) buffer MeshDraws { uint meshDraws[]; };          // per model × 2: VkDrawIndexedIndirectCommand; then per model × 2 the cores
layout(set = 1, binding = 6, std430) buffer ImpostorDraws { uint impostorDraws[]; };  // per model, then per cascade and model: VkDrawIndexedIndirectCommand
layout(set = 1, binding = 7, std430) buffer TreeCounters { uint treeCounters[]; };    // instances, full, reduced, impostor, dropped

layout(push_constant) uniform Push { uint mode; } push;

void append(uint model, uint lod, uint instance, float threshold, vec2 wind) {
  uint slot = lod < 2u ? atomicAdd(meshDraws[(model * 2u + lod) * 5u + 1u], 1u)
                       : atomicAdd(impostorDraws[model * 5u + 1u], 1u);
  if (slot >= treeRegionCapacity(lod)) {
    atomicAdd(treeCounters[4], 1u);
    return;
  }
  treeVisible[treeRegionBase(model, lod) + slot] =
      uvec4(instance, floatBitsToUint(threshold), floatBitsToUint(wind.x), floatBitsToUint(wind.y));
  atomicAdd(treeCounters[1u + lod], 1u);
}

// Into each cascade whose box (frame.shadowMatrices: x, y in [−1, 1], depth in [0, 1]) the tree's
// sphere reaches. The matrices' rows are the light's axes over the box's half extents, so a
// radius in metres is that many times their length in clip units.
void castShadow(uint model, uint instance, float keep, vec2 wind, vec3 centre, float radius) {
  uint drawn = uint(frame.shadowTexel.w);  // a cascade kept from an earlier frame needs no casters
  for (uint c = 0u; c < kTreeShadowCascades; ++c) {
    if ((drawn & (1u << c)) == 0u) continue;
    mat4 m = frame.shadowMatrices[c];
    vec4 p = m * vec4(centre, 1.0);
    vec3 r = radius * vec3(length(vec3(m[0][0], m[1][0], m[2][0])), length(vec3(m[0][1], m[1][1], m[2][1])),
                           length(vec3(m[0][2], m[1][2], m[2][2])));
    if (any(greaterThan(abs(p.xy), vec2(1.0) + r.xy)) || p.z < -r.z || p.z > 1.0 + r.z) continue;
    uint command = treeCasterCommand(c, model) * 5u;
    uint slot = atomicAdd(impostorDraws[command + 1u], 1u);
    if (slot >= treeCasterCapacity(c)) {
      atomicAdd(treeCounters[4], 1u);
      continue;
    }
    treeVisible[impostorDraws[command + 4u] + slot] =
        uvec4(instance, floatBitsToUint(keep), floatBitsToUint(wind.x), floatBitsToUint(wind.y));
    atomicAdd(treeCounters[5u + c], 1u);
  }
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (push.mode == 1u) {  // finish: no draw reads past its region
    if (i < trees.counts.y) {
      for (uint lod = 0u; lod < 2u; ++lod) {
        meshDraws[(i * 2u + lod) * 5u + 1u] = min(meshDraws[(i * 2u + lod) * 5u + 1u], treeRegionCapacity(lod));
        // The crowns' cores: the same lists (render/tree_pass.cpp draws them first).
        meshDraws[((trees.counts.y + i) * 2u + lod) * 5u + 1u] = meshDraws[(i * 2u + lod) * 5u + 1u];
      }
      impostorDraws[i * 5u + 1u] = min(impostorDraws[i * 5u + 1u], trees.capacity.z);
      for (uint c = 0u; c < kTreeShadowCascades; ++c) {
        uint at = treeCasterCommand(c, i) * 5u + 1u;
        impostorDraws[at] = min(impostorDraws[at], treeCasterCapacity(c));
      }
    }
    return;
  }
  if (i >= trees.counts.x) return;
  if (i % kTreePageSize >= pageCounts[i / kTreePageSize]) return;
  atomicAdd(treeCounters[0], 1u);
  TreeInstanceGpu t = treeInstances[i];
  vec3 rel = t.position - trees.camera.xyz;
  float dist = length(rel);
  float h = max(t.heightM, 0.5);
  // Trees end at the horizon, or sooner where they are a pixel or two tall. (Ending them by the
  // crown where it is wider than the tree is tall, as from above, was tried: it drew more
  // impostors in every bundled flight for trees of a pixel or two; not kept.)
  float horizon = min(trees.lod.z, trees.limits.y * h);
  if (dist >= horizon) return;
  vec3 centre = rel + vec3(0.0, 0.0, 0.5 * h);
  // The model's box as drawn (treeScale), with a tenth more for the lean and the sway.
  float reach = 1.1 * length(vec2(treeScale(t, trees.models[t.model]).x * trees.models[t.model].shape.y, 0.5 * h));
  float radius = reach + trees.limits.x;
  for (int p = 0; p < 6; ++p)
    if (dot(trees.frustum[p].xyz, centre) + trees.frustum[p].w < -radius) return;

  vec2 wind = vec2(0.0);
  if ((sim.counts.z & kSimFlagWind) != 0) wind = windAt(t.position.xy, treeTime()).xy;
  float d = dist / h;  // distance in tree heights
  float a = trees.lod.x, b = trees.lod.y, share = trees.lod.w;
  float keep = 1.0;  // the shadow's share: the tree's own, whatever levels cross-fade
  if ((trees.counts.z & kTreeFlagFades) == 0u) {
    append(t.model, d < a ? kTreeLodFull : (d < b ? kTreeLodReduced : kTreeLodImpostor), i, 1.0, wind);
  } else if (d < a * (1.0 - share)) {
    append(t.model, kTreeLodFull, i, 1.0, wind);
  } else if (d < a) {
    float f = (d - a * (1.0 - share)) / (a * share);
    append(t.model, kTreeLodFull, i, 1.0 + f, wind);
    append(t.model, kTreeLodReduced, i, f, wind);
  } else if (d < b * (1.0 - share)) {
    append(t.model, kTreeLodReduced, i, 1.0, wind);
  } else if (d < b) {
    float f = (d - b * (1.0 - share)) / (b * share);
    append(t.model, kTreeLodReduced, i, 1.0 + f, wind);
    append(t.model, kTreeLodImpostor, i, f, wind);
  } else {
    keep = clamp((horizon - dist) / (horizon * share), 0.0, 1.0);
    if (keep > 0.0) append(t.model, kTreeLodImpostor, i, keep, wind);
  }
  // Where its fragments may fall, so the terrain's depth is written there before the trees are
  // drawn (render/terrain_depth_handover.h): the model's sphere with a quarter more, and the
  // impostor's own (its extent plus a tenth of the height for the sway, tree_impostor.vert).
  if (keep > 0.0) markSphere(centre, 1.25 * reach + 0.1 * h);
  // The caster's own sphere (its quad turned to the sun, with the sway), not the view's margin.
  if (frame.shadowSplits.w > 0.5 && keep > 0.0) castShadow(t.model, i, keep, wind, centre, reach);
}
