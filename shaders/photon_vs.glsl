// Caustics mapping after Shah et al. 2007: one photon per texel of the water seen from the sun.
// It is refracted at the surface, and its landing point on the terrain is found by iterating
// on the receiver map (the terrain's positions seen from the sun); it is splatted there, so a
// flat surface puts exactly one photon on every texel and focusing waves put more.
uniform sampler2D waterPosition, waterNormal, receiver;
uniform ivec2 mapSize;
uniform mat4 lightClipFromWorld;
uniform vec3 sunDir;  // towards the sun

vec2 project(vec3 p) {
  vec4 l = lightClipFromWorld * vec4(p, 1.0);
  return l.xy / l.w * 0.5 + 0.5;
}

void main() {
  ivec2 texel = ivec2(gl_VertexID % mapSize.x, gl_VertexID / mapSize.x);
  vec4 p = texelFetch(waterPosition, texel, 0);
  gl_PointSize = 1.0;
  if (p.w < 0.5) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }  // no water: clipped
  vec3 n = normalize(texelFetch(waterNormal, texel, 0).xyz);
  if (dot(n, sunDir) < 0.0) n = -n;
  vec3 t = refract(-sunDir, n, 1.0 / 1.33);
  if (dot(t, t) == 0.0) t = -sunDir;
  // First guess: the receiver straight below (along the light) is as far as the landing point.
  vec3 q = texture(receiver, project(p.xyz)).xyz;
  float d = distance(p.xyz, q);
  for (int k = 0; k < 3; ++k) {
    q = p.xyz + d * t;
    vec3 r = texture(receiver, project(q)).xyz;
    d = distance(p.xyz, r);
  }
  q = p.xyz + d * t;
  gl_Position = lightClipFromWorld * vec4(q, 1.0);
}
