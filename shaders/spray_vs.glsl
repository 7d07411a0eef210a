// Spray: the particles the water surface does not cover (a jet in flight, drops, a thin sheet
// below the grid's resolution), drawn as sprites. Each reads the density grid the surface was
// extracted from, trilinearly at its position: at or above half the iso level it lies inside the
// surface or just beside it (on a coarse grid the water's rim reads a little below the level),
// which already shows it, and it is not drawn (moved out of the clip volume).
layout(location = 0) in vec4 position;  // xyz; the surface's particle buffer
layout(std430, binding = 1) readonly buffer Density { uint density[]; };
uniform mat4 clipFromWorld;
uniform float pointSize;  // pixels at distance 1
uniform vec3 origin;
uniform float cell;
uniform ivec3 nodes;
uniform float isoFixed;  // the iso level in the grid's fixed-point units
out float shade;
void main() {
  vec3 g = (position.xyz - origin) / cell;
  bool inGrid = all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(nodes - 1)));
  float v = 0.0;
  if (inGrid) {
    ivec3 i0 = clamp(ivec3(floor(g)), ivec3(0), nodes - 2);
    vec3 t = clamp(g - vec3(i0), 0.0, 1.0);
    for (int k = 0; k < 8; ++k) {
      ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
      ivec3 n = i0 + o;
      vec3 w = mix(1.0 - t, t, vec3(o));
      v += w.x * w.y * w.z * float(density[(n.z * nodes.y + n.y) * nodes.x + n.x]);
    }
  }
  if (inGrid && v >= 0.5 * isoFixed) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // inside the surface: clipped away
    gl_PointSize = 1.0;
    shade = 0.0;
    return;
  }
  gl_Position = clipFromWorld * vec4(position.xyz, 1.0);
  gl_PointSize = max(pointSize / gl_Position.w, 2.0);
  shade = clamp(2.0 * v / max(isoFixed, 1.0), 0.0, 1.0);  // the thinner, the paler
}
