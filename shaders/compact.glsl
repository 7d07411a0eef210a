// Lists the occupied blocks. The list's head is the count and then an indirect dispatch command
// that finish.glsl fills in, so marching tetrahedra is dispatched over the list without a CPU
// readback.
layout(local_size_x = 256) in;

layout(std430, binding = 2) readonly buffer Occupancy { uint occupied[]; };
layout(std430, binding = 3) buffer BlockList { uint count; uint dispatch[3]; uint block[]; };

uniform uint blockCount;

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= blockCount || occupied[b] == 0u) return;
  block[atomicAdd(count, 1u)] = b;
}
