// Spray sprites: round drops of white water, shaded as small spheres.
in float shade;
out vec4 colour;
void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  vec3 c = mix(vec3(0.93, 0.97, 1.0), vec3(0.55, 0.75, 0.92), shade);
  colour = vec4(c * (0.7 + 0.3 * sqrt(1.0 - r2)), 1.0);
}
