in float value;
out vec4 colour;
void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  if (dot(d, d) > 1.0) discard;
  // Blue (0) through white to brown (1): clear water to laden water.
  vec3 c = value < 0.5 ? mix(vec3(0.15, 0.35, 0.90), vec3(0.95), value * 2.0)
                       : mix(vec3(0.95), vec3(0.55, 0.32, 0.10), value * 2.0 - 1.0);
  colour = vec4(c * (0.75 + 0.25 * sqrt(1.0 - dot(d, d))), 1.0);
}
