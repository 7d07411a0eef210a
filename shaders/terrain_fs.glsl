// Terrain colour: a height/slope ramp (mode 0), erosion and deposition since the start in false
// colour (mode 1: red erosion, blue deposition, as the paper's Figs. 1 and 8), or the deposited
// sediment alone (mode 2). Sun and sky light, and under water the caustics map.
in vec3 worldPos;
in vec3 worldNormal;
in vec2 gridCoord;

uniform sampler2D change;      // R32F height change since the start [m]
uniform int mode;
uniform float changeScale;     // |Δh| that gets the full colour [m]
uniform vec2 heightRange;      // lowest, highest terrain height
uniform vec3 sunDir;           // towards the sun
uniform bool caustics;
uniform sampler2D causticMap;  // photons per texel from the water, 1 = flat water
uniform sampler2D waterFromLight;  // xyz water surface seen from the sun, w = 1 where water
uniform mat4 lightClipFromWorld;
uniform float causticStrength;

out vec4 colour;

vec3 ramp(float t, float slope) {
  vec3 low = vec3(0.76, 0.70, 0.50), mid = vec3(0.42, 0.55, 0.30), high = vec3(0.60, 0.52, 0.44);
  vec3 c = t < 0.5 ? mix(low, mid, t * 2.0) : mix(mid, high, t * 2.0 - 1.0);
  return mix(c, vec3(0.50, 0.45, 0.42), smoothstep(0.5, 0.9, slope));  // steep: bare rock
}

void main() {
  vec3 n = normalize(worldNormal);
  float t = clamp((worldPos.y - heightRange.x) / max(heightRange.y - heightRange.x, 1e-6), 0.0, 1.0);
  float slope = 1.0 - n.y;
  vec3 base = ramp(t, slope);
  float dh = texelFetch(change, ivec2(gridCoord + 0.5), 0).r;
  if (mode == 1) {
    float e = clamp(-dh / changeScale, 0.0, 1.0), d = clamp(dh / changeScale, 0.0, 1.0);
    base = mix(vec3(0.92), vec3(0.85, 0.08, 0.05), sqrt(e));
    base = mix(base, vec3(0.10, 0.25, 0.90), sqrt(d));
  } else if (mode == 2) {
    base = mix(base * 0.6, vec3(0.95, 0.80, 0.35), sqrt(clamp(dh / changeScale, 0.0, 1.0)));
  }
  float sun = max(dot(n, sunDir), 0.0);
  if (caustics) {
    vec4 l = lightClipFromWorld * vec4(worldPos, 1.0);
    vec2 uv = l.xy / l.w * 0.5 + 0.5;
    vec4 water = texture(waterFromLight, uv);
    if (water.w > 0.5 && water.y > worldPos.y)  // under water: the sun arrives as caustics
      sun *= mix(1.0, texture(causticMap, uv).r, causticStrength);
  }
  colour = vec4(base * (0.35 + 0.65 * sun), 1.0);
}
