// The shared simulation's GPU data layout (issue 19), one text for GLSL and C++
// (simulation/shared_code.h): the grids' sizes, the per-frame simulation block (std140: vec4 and
// ivec4 members only, so C++ and GLSL lay it out alike) and the records of the wind grid and the
// virtual blades (std430).
//
// World anchoring. Both grids are aligned to the scene's local ENU frame (x east, y north) and
// toroidal: world cell c lives at index c mod N, so a camera move rewrites only the cells that
// entered the window and a point keeps its value whichever camera sees it. Positions reach the GPU
// camera-relative; a cell's index is the camera's world cell (integer, from the CPU) plus the floor
// of the camera's offset inside it plus the relative position, so indexing never needs large
// floats.

#include "shared_code_macros.glsl"

// The wind grid: virtual blades at the centres of 4 m cells, 128 × 128 around the camera (512 m:
// past the plants' 250 m horizon on every side).
const int kWindGrid = 128;
const float kWindCellM = 4.0f;
// The interaction field: 0.1 m cells in 32 × 32 tiles of 32 × 32 texels (3.2 m) around the camera
// (102.4 m: trails show to 51 m away); tiles that leave it with a trail go to the trail store
// (simulation/interaction_window.h).
const int kFieldTileTexels = 32;
const int kFieldWindowTiles = 32;
const int kFieldSize = 1024;  // kFieldTileTexels * kFieldWindowTiles
const float kFieldCellM = 0.1f;
// Fixed sub-steps: a frame runs floor(t / kSubstepS) − (steps so far) of them, at most
// kMaxSubsteps (a longer frame slows the simulation down rather than destabilising it).
const int kSubstepsPerS = 240;
const float kSubstepS = 1.0f / 240.0f;
const int kMaxSubsteps = 60;
const int kBladeHinges = 4;
const int kMaxWindSources = 8;
const int kMaxColliders = 8;

const int kSourceFan = 1;
const int kSourceWhirlwind = 2;
const int kSourceRotor = 3;

const int kSimFlagWind = 1;         // the wind or a source blows: plants read the moments
const int kSimFlagInteraction = 2;  // the interaction field may hold trails, or colliders exist

struct WindSourceGpu {
  vec4 position;  // xy: world (m), z: hub height above the ground (m), w: radius (m)
  vec4 params;    // x: type (kSource*), y: strength (m/s), zw: fan: unit direction it blows towards
};

struct ColliderGpu {
  vec4 centre;    // xyz: camera-relative (m), w: radius (m)
  vec4 shape;     // x: half the capsule's axis (0: sphere), y: camera-relative ground z under it, z: strength, w: 1 if `previous` holds
  vec4 previous;  // xyz: camera-relative centre one frame ago (the swept stamp), w: unused
};

struct SimulationParams {
  vec4 wind;          // xy: mean wind (m/s, towards; x east, y north), z: gustiness 0 … 1, w: unused
  vec4 clock;         // x: sub-steps this frame, y: the first sub-step's start time (s), z: kSubstepS, w: frame time (s)
  ivec4 windCells;    // xy: the camera's world cell, zw: the window's first world cell
  vec4 camera;        // xyz: camera position in the world (m; float is enough for the wind's scales), w: unused
  vec4 windCamera;    // xy: camera position minus its wind cell's corner (m), zw: unused
  ivec4 fieldTexels;  // xy: the camera's world texel, zw: the window's first world tile
  vec4 field;         // xy: camera minus its texel's corner (m), z: the decay this frame (cs units), w: recovery per s
  ivec4 counts;       // x: wind sources, y: colliders, z: kSimFlag* bits, w: unused
  WindSourceGpu sources[kMaxWindSources];
  ColliderGpu colliders[kMaxColliders];
  vec4 restoredDecay[256];  // 1024 window tiles: cs to take off tiles restored from the store this frame
};

// The virtual blade of one wind cell: per hinge its lean ψ (xy, rad) and rate ω (zw, rad/s);
// cell.xy its world cell, cell.z 1 once initialised.
struct VirtualBladeGpu {
  vec4 hinge[kBladeHinges];
  ivec4 cell;
};

// What drawn plants read per wind cell: the wind (xyz m/s at the end of the frame's steps) and
// each hinge's moment as the reference blade's equivalent lean (rad; simulation/shared/virtual_blade.glsl).
struct WindCellGpu {
  vec4 wind;
  vec4 moments01;  // xy: hinge 0, zw: hinge 1
  vec4 moments23;  // xy: hinge 2, zw: hinge 3
};
