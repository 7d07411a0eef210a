// The terrain: two triangles per heightfield cell (diagonal (i,k)–(i+1,k+1), as the engine's),
// made from gl_VertexID with the heights in a texture. No vertex buffer.
uniform sampler2D heights;  // R32F, nx × nz
uniform ivec2 size;         // nx, nz
uniform vec2 origin;        // x0, z0
uniform vec2 spacing;       // dx, dz
uniform mat4 clipFromWorld;

out vec3 worldPos;
out vec3 worldNormal;
out vec2 gridCoord;

const ivec2 kCorner[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

float heightAt(ivec2 v) { return texelFetch(heights, clamp(v, ivec2(0), size - 1), 0).r; }

void main() {
  int cell = gl_VertexID / 6;
  ivec2 v = ivec2(cell % (size.x - 1), cell / (size.x - 1)) + kCorner[gl_VertexID % 6];
  worldPos = vec3(origin.x + spacing.x * v.x, heightAt(v), origin.y + spacing.y * v.y);
  // Central differences (one-sided at the edges).
  float dhdx = (heightAt(v + ivec2(1, 0)) - heightAt(v - ivec2(1, 0))) /
               (spacing.x * float(min(v.x + 1, size.x - 1) - max(v.x - 1, 0)));
  float dhdz = (heightAt(v + ivec2(0, 1)) - heightAt(v - ivec2(0, 1))) /
               (spacing.y * float(min(v.y + 1, size.y - 1) - max(v.y - 1, 0)));
  worldNormal = normalize(vec3(-dhdx, 1.0, -dhdz));
  gridCoord = vec2(v);
  gl_Position = clipFromWorld * vec4(worldPos, 1.0);
}
