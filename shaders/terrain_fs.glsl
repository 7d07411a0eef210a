// Terrain colour: a height/slope ramp (mode 0), erosion and deposition since the start in false
// colour (mode 1: red erosion, blue deposition, as the paper's Figs. 1 and 8), or the deposited
// sediment alone (mode 2), or an erosion map (mode 3: dark where 0, then blue through green to
// yellow by √(value / largest); a direction map by hue, east red). Sun and sky light, and under
// water the caustics map.
in vec3 worldPos;
in vec3 worldNormal;
in vec2 gridCoord;

uniform sampler2D change;      // R32F height change since the start [m]
uniform int mode;
uniform sampler2D map;         // R32F an erosion map's value per vertex (mode 3)
uniform sampler2D map2;        // R32F its second channel (a direction's z)
uniform float mapScale;        // the map's largest |value|
uniform bool mapPair;          // a direction (x in map, z in map2)
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
  } else if (mode == 3) {
    ivec2 at = ivec2(gridCoord + 0.5);
    float a = texelFetch(map, at, 0).r, b = texelFetch(map2, at, 0).r;
    if (mapPair) {
      if (a != 0.0 || b != 0.0) {
        float hue = atan(b, a) / 6.2831853 + 0.5;  // the direction's angle, 0 … 1
        base = clamp(abs(fract(hue + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
      } else {
        base *= 0.45;
      }
    } else if (a > 0.0) {
      float t = sqrt(clamp(a / mapScale, 0.0, 1.0));
      vec3 lo = vec3(0.15, 0.20, 0.65), mid = vec3(0.10, 0.65, 0.55), hi = vec3(0.98, 0.90, 0.15);
      base = t < 0.5 ? mix(lo, mid, t * 2.0) : mix(mid, hi, t * 2.0 - 1.0);
    } else {
      base *= 0.45;
    }
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
