// Seen from the sun: the water surface's position (w = 1) and normal per texel.
in vec3 worldPos;
in vec3 worldNormal;
layout(location = 0) out vec4 position;
layout(location = 1) out vec4 normal;
void main() {
  position = vec4(worldPos, 1.0);
  normal = vec4(normalize(worldNormal), 0.0);
}
