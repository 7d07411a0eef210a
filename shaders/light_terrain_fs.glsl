// Seen from the sun: the terrain's world position per texel (the caustics' receiver map).
in vec3 worldPos;
in vec3 worldNormal;
in vec2 gridCoord;
out vec4 position;
void main() { position = vec4(worldPos, 1.0); }
