// Density splatting (paper §5): every particle adds its SPH density contribution m·W_poly6(r, h)
// (the simulation's kernel) to the grid nodes within h, as fixed point (integer atomics: the sum
// is exact and independent of order). It also marks, in the occupancy grid 4× coarser, every
// block holding a cell that has one of these nodes as a corner.
layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Particles { vec4 particle[]; };
layout(std430, binding = 1) buffer Density { uint density[]; };
layout(std430, binding = 2) buffer Occupancy { uint occupied[]; };

uniform uint count;
uniform vec3 origin;
uniform float cell;
uniform ivec3 nodes;   // grid nodes per axis
uniform ivec3 blocks;  // occupancy blocks per axis (4 cells each)
uniform float h;
uniform float weight;  // m · 315 / (64 π h⁹) / ρ0 · fixed-point scale

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  vec3 p = particle[i].xyz;
  ivec3 lo = max(ivec3(ceil((p - h - origin) / cell)), ivec3(0));
  ivec3 hi = min(ivec3(floor((p + h - origin) / cell)), nodes - 1);
  if (any(greaterThan(lo, hi))) return;
  float h2 = h * h;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        vec3 d = p - (origin + cell * vec3(x, y, z));
        float r2 = dot(d, d);
        if (r2 >= h2) continue;
        float w = h2 - r2;
        atomicAdd(density[(z * nodes.y + y) * nodes.x + x], uint(weight * w * w * w + 0.5));
      }
  // Cells lo − 1 … hi have a corner among the nodes lo … hi.
  ivec3 bl = max(lo - 1, ivec3(0)) / 4, bh = min(hi, nodes - 2) / 4;
  for (int z = bl.z; z <= bh.z; ++z)
    for (int y = bl.y; y <= bh.y; ++y)
      for (int x = bl.x; x <= bh.x; ++x) occupied[(z * blocks.y + y) * blocks.x + x] = 1u;
}
