// The terrain's colour at one surface point, shared by the forward fragment shader
// (terrain.frag) and the deferred compute shade (terrain_shade.glsl), so both paths shade with
// one piece of code. Needs frame_uniforms.glsl, atmosphere.glsl, colour_score.glsl,
// terrain_detail.glsl and terrain_palette.glsl. Sets 1 (imagery) and 2 (detail) as in the
// terrain pass.
layout(set = 1, binding = 0) uniform sampler2DArray imagery;  // one tile per layer; sRGB: sampled as linear colour
// Each imagery layer's NDVI (R8, datasets/tile_codec.h's bytes, 0 = none; one cleared layer when
// the dataset has none): the detail blend scores it like the species choice does.
layout(set = 1, binding = 1) uniform sampler2DArray ndviLayers;

// The NDVI at layer uv, nearest texel (a filtered byte would blend "none" into values); kNoNdvi
// where there is none.
float terrainNdvi(vec2 uv, float layer) {
  ivec3 size = textureSize(ndviLayers, 0);
  ivec2 t = clamp(ivec2(uv * vec2(size.xy)), ivec2(0), size.xy - 1);
  return ndviOfTexel(texelFetch(ndviLayers, ivec3(t, min(int(layer), size.z - 1)), 0).r);
}
layout(set = 2, binding = 0) uniform sampler2DArray detailTextures;  // one layer per detail surface; UNORM, 0.5 = neutral

// The imagery is the ground's albedo (issue 39 item 4): the importer turned it into reflectance
// and took the shading it was photographed under out of it (datasets/README.md), so it is lit
// here once, by this frame's sun and sky (atmosphere.glsl), as a Lambertian surface.

// What the shading needs of a surface point: its attributes as the vertex stage interpolates
// them, its piece's imagery mapping (terrain_piece.glsl), and the screen derivatives of its
// camera-relative position (for the detail textures' filtering).
struct TerrainPoint {
  vec3 offset;     // camera-relative position (m)
  vec3 normal;     // interpolated, not yet normalised
  float heightMsl;
  vec2 uv;         // the piece's imagery uv
  vec3 offsetDx;   // d offset / d pixel x
  vec3 offsetDy;   // d offset / d pixel y
};
struct TerrainImagery {
  vec4 imageryUv;   // layer uv = uv · xy + zw
  vec4 previousUv;  // the same for the layer it fades from
  vec4 layers;      // x: imagery layer (−1 none), y: previous layer (−1 none), z: blend
};

// Close-up detail (core seed 001 §3.3): the detail surfaces blended by the colour-score weights
// of the base colour, as a factor on the albedo (2 × texel: 0.5 is neutral). Tiled in world
// space — frame.detail holds the camera position modulo the period, so the pattern does not swim
// — at two scales, projected triplanar so cliffs are not smeared, and faded out with distance so
// far terrain is exactly the imagery. `world`, `dx`, `dy`: position in periods and its screen
// derivatives.
vec3 detailFactor(vec3 baseLinear, float ndvi, vec3 n, float distanceM, vec3 world, vec3 dx, vec3 dy) {
  float fade = (1.0 - smoothstep(detail.params.y, detail.params.z, distanceM)) * detail.params.w * frame.detail.w;
  if (fade <= 0.0) return vec3(1.0);
  vec4 surfaces = detailSurfaceWeights(hsvFromLinear(baseLinear), ndvi);
  vec3 planes = pow(abs(n), vec3(4.0));
  planes /= planes.x + planes.y + planes.z;  // x: the yz plane, y: xz, z: xy (flat ground)
  float fine = detail.tiling.y, coarse = detail.tiling.z, coarseShare = detail.tiling.w;
  vec3 factor = vec3(0.0);
  for (int layer = 0; layer < kDetailSurfaces; ++layer) {
    float w = surfaces[layer];
    if (w < 1e-3) {  // negligible: count it as neutral rather than sample it
      factor += w;
      continue;
    }
    vec3 texel = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis) {
      if (planes[axis] < 1e-3) continue;
      vec2 uv = axis == 0 ? world.yz : (axis == 1 ? world.xz : world.xy);
      vec2 ux = axis == 0 ? dx.yz : (axis == 1 ? dx.xz : dx.xy);
      vec2 uy = axis == 0 ? dy.yz : (axis == 1 ? dy.xz : dy.xy);
      vec3 a = textureGrad(detailTextures, vec3(uv * fine, layer), ux * fine, uy * fine).rgb;
      vec3 b = textureGrad(detailTextures, vec3(uv * coarse, layer), ux * coarse, uy * coarse).rgb;
      texel += planes[axis] * mix(a, b, coarseShare);
    }
    factor += w * 2.0 * texel;
  }
  return mix(vec3(1.0), factor, fade);
}

// The lit, fogged colour (linear) of the terrain at `p`. The imagery has one mip level, so
// sampling it at level 0 is what implicit derivatives would pick too (and compute has none).
vec3 shadeTerrain(TerrainPoint p, TerrainImagery im) {
  vec3 n = normalize(p.normal);
  float slope = 1.0 - clamp(n.z, 0.0, 1.0);  // 0 flat … 1 vertical
  vec3 albedo = terrainAlbedo(p.heightMsl, slope);
  vec3 base = albedo;  // the ground's colour as imaged: what the colour score reads
  float ndvi = kNoNdvi;
  if (im.layers.x >= 0.0) {
    vec4 photo = textureLod(imagery, vec3(p.uv * im.imageryUv.xy + im.imageryUv.zw, im.layers.x), 0.0);
    ndvi = terrainNdvi(p.uv * im.imageryUv.xy + im.imageryUv.zw, im.layers.x);
    if (im.layers.y >= 0.0 && im.layers.z < 1.0) {  // a finer tile fading in over its ancestor
      vec4 before = textureLod(imagery, vec3(p.uv * im.previousUv.xy + im.previousUv.zw, im.layers.y), 0.0);
      photo = mix(before, photo, im.layers.z);
    }
    base = mix(albedo, photo.rgb, photo.a);
    albedo = mix(albedo, photo.rgb, photo.a);  // alpha 0: no imagery there
  }
  vec3 world = (frame.detail.xyz + p.offset) / detail.tiling.x;
  albedo *= detailFactor(base, ndvi, n, length(p.offset), world, p.offsetDx / detail.tiling.x, p.offsetDy / detail.tiling.x);
  float sun = max(dot(n, frame.sunDirection.xyz), 0.0) * sunShadow(p.offset, n);
  vec3 lit = albedo / kAtmospherePi * (sunIlluminance() * sun + skyIrradiance(n));
  return applyAerialPerspective(lit, p.offset);
}
