#ifndef TREE_IMPOSTOR_GLSL
#define TREE_IMPOSTOR_GLSL
// Octahedral impostors (issue 20; Ryan Brucks' hemi-octahedral impostors): each model is captured
// at start-up from G × G directions over the upper hemisphere (render/tree_impostors.h), cell (i, j)
// looking from treeImpostorDirection((i + ½) / G, (j + ½) / G), orthographic over a square of half
// extent R around the model's centre, in the basis treeImpostorBasis gives. At run time a tree
// shows the cell nearest the direction it is seen from, on a quad in that cell's basis.

// Unit direction (z ≥ 0) ↔ [0, 1]²: the hemisphere's octahedral map turned by 45° to fill the square.
vec2 treeImpostorUv(vec3 d) {
  d.z = max(d.z, 0.0);
  vec2 p = d.xy / (abs(d.x) + abs(d.y) + d.z);
  return vec2(p.x + p.y, p.x - p.y) * 0.5 + 0.5;
}
vec3 treeImpostorDirection(vec2 uv) {
  vec2 ab = uv * 2.0 - 1.0;
  vec2 p = vec2(ab.x + ab.y, ab.x - ab.y) * 0.5;
  return normalize(vec3(p, 1.0 - abs(p.x) - abs(p.y)));
}
// The image axes of a view along −d (d: towards the viewer): right is horizontal, up as vertical
// as the view allows.
void treeImpostorBasis(vec3 d, out vec3 right, out vec3 up) {
  vec3 r = cross(vec3(0.0, 0.0, 1.0), d);
  right = dot(r, r) > 1e-6 ? normalize(r) : vec3(1.0, 0.0, 0.0);
  up = cross(d, right);
}
#endif
