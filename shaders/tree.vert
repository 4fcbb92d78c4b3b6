#version 460
#extension GL_GOOGLE_include_directive : require
// Tree models' vertices (common/tree_vertex.glsl), where the device has no clip distances: the
// near fade is then the fragment stage's alone (tree.frag).
#include "common/tree_vertex.glsl"
