// The particle view: point sprites coloured by sediment concentration C or speed.
layout(location = 0) in vec4 position;  // xyz, w = the value to colour by
uniform mat4 clipFromWorld;
uniform float pointSize;  // pixels at distance 1
uniform vec2 valueRange;
out float value;
void main() {
  gl_Position = clipFromWorld * vec4(position.xyz, 1.0);
  gl_PointSize = max(pointSize / gl_Position.w, 1.0);
  value = clamp((position.w - valueRange.x) / max(valueRange.y - valueRange.x, 1e-12), 0.0, 1.0);
}
