#version 450
// Plant pipelines: one patch (one control point) per classified group; the instance is the
// group's index in its species' buffer (render/plant_pass.h).
layout(location = 0) out uint outGroup;
void main() {
  outGroup = uint(gl_InstanceIndex);
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
