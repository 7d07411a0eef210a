// Water shading (paper §5): Fresnel blend of a cube-map reflection and a refraction that
// perturbs the texture coordinates of the background (terrain) render by the surface normal,
// absorbed with the water's thickness; a sun highlight. Each effect can be off.
in vec3 worldPos;
in vec3 worldNormal;

uniform vec3 eye;
uniform vec3 sunDir;
uniform bool reflections;
uniform bool refraction;
uniform samplerCube sky;
uniform sampler2D background;       // the terrain render
uniform sampler2D backgroundDepth;  // its depth
uniform vec2 viewport;
uniform vec2 nearFar;
uniform float refractionStrength;

out vec4 colour;

float linearDepth(float d) {
  float z = d * 2.0 - 1.0;
  return 2.0 * nearFar.x * nearFar.y / (nearFar.y + nearFar.x - z * (nearFar.y - nearFar.x));
}

void main() {
  vec3 n = normalize(worldNormal);
  vec3 v = normalize(eye - worldPos);
  if (dot(n, v) < 0.0) n = -n;  // seen from inside (a splash): shade the side we see
  const vec3 deep = vec3(0.05, 0.22, 0.32);
  float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
  vec3 reflected = reflections ? texture(sky, reflect(-v, n)).rgb : vec3(0.55, 0.70, 0.85);
  vec3 body;
  if (refraction) {
    vec2 uv = gl_FragCoord.xy / viewport;
    float here = linearDepth(gl_FragCoord.z);
    float behind = linearDepth(texture(backgroundDepth, uv).r);
    vec2 shifted = clamp(uv + n.xz * refractionStrength * min(behind - here, 1.0), 0.0, 1.0);
    // Do not pull in what lies in front of the water.
    if (linearDepth(texture(backgroundDepth, shifted).r) < here) shifted = uv;
    float thickness = max(linearDepth(texture(backgroundDepth, shifted).r) - here, 0.0);
    vec3 seen = texture(background, shifted).rgb;
    body = mix(deep, seen * vec3(0.75, 0.92, 0.95), exp(-3.0 * thickness));
  } else {
    body = deep;
  }
  vec3 c = mix(body, reflected, fresnel);
  c += vec3(1.0, 0.95, 0.85) * pow(max(dot(reflect(-sunDir, n), v), 0.0), 200.0);
  colour = vec4(c, 1.0);
}
