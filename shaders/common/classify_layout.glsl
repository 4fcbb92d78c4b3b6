// Layouts of the classify pass's buffers: the GLSL side of render/classify_layout.h (sizes
// checked there).

const uint kMaxSpecies = 16u;

struct SeedTriangle {
  vec4 v0;    // xyz apex relative to the camera; w plant count N
  vec4 v1;
  vec4 v2;
  vec4 uv01;
  vec2 uv2;
  uint keyLo, keyHi;
  int layer;
  float lodCount;  // eq. 1 / 2: each species' own count (speciesPlantCount)
  float areaM2;
  float nearestM;
  vec4 previousUv01;  // the imagery drawn before, while it changes: plants cross-fade
  vec2 previousUv2;
  int previousLayer;  // −1: none (then imageryBlend is a fade-in)
  float imageryBlend;
};

struct PlantCluster {
  uint triangle, cluster, firstSeed, seedCount;
  uint species;
  float sPrime;
  float fade;
  uint pad;
};

struct Species {
  vec4 reference;        // HSV, w: p
  vec4 weights;          // w: ln threshold
  uvec4 flags;           // x bare (or a tree), y kind, z casts planar shadows, w a tree
  vec4 heightStiffness;
  vec4 widthColour;
  vec4 marker;
  vec4 ground;           // x plants per m², y horizon (m), z NDVI reference, w NDVI weight
  vec4 index;            // x excess-green reference, y its weight (colour_score.h)
};
