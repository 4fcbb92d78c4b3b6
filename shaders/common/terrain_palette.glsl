// Colour by height and slope, until imagery colours the terrain (dataset issue): pale desert
// floor low down, red sandstone on steep walls, dark green forest on the high plateau.
vec3 terrainAlbedo(float heightMsl, float slope) {
  vec3 floorColor = vec3(0.34, 0.24, 0.15);
  vec3 plateau = vec3(0.10, 0.15, 0.06);
  vec3 rock = vec3(0.45, 0.17, 0.08);
  vec3 pale = vec3(0.55, 0.47, 0.36);
  float t = smoothstep(1300.0, 2200.0, heightMsl);
  vec3 ground = mix(floorColor, plateau, t);
  vec3 wall = mix(rock, pale, smoothstep(1800.0, 2300.0, heightMsl));
  return mix(ground, wall, smoothstep(0.25, 0.55, slope));
}
