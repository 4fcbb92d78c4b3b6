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
  uint pad0, pad1, pad2;
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
  uvec4 flags;           // x bare, y kind
  vec4 heightStiffness;
  vec4 widthColour;
  vec4 marker;
};
