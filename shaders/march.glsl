// Marching tetrahedra (paper §5): one work group per block of 4 × 4 × 4 cells, one invocation per
// cell. Each cube is cut into the six tetrahedra around its diagonal 0–7 (the same cut in every
// cube, so faces match and the surface is closed). A tetrahedron whose corners straddle the iso
// level gives one or two triangles, appended with an atomic counter that is also the vertex count
// of the indirect draw command. Edge points are interpolated from the edge's lower-index node, so
// both cells sharing an edge compute the same point bit for bit. Normals: the density gradient
// (central differences at the nodes, interpolated), pointing out of the water.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = 1) readonly buffer Density { uint density[]; };
layout(std430, binding = 3) readonly buffer BlockList { uint count; uint dispatch[3]; uint block[]; };
struct Vertex { vec4 position; vec4 normal; };
layout(std430, binding = 4) buffer Vertices { Vertex vertex[]; };
// DrawArraysIndirectCommand, then the number of triangles that did not fit, then the number of
// iso-cubes (cells the surface crosses) found in count-only mode.
layout(std430, binding = 5) buffer Draw { uint vertexCount; uint instanceCount; uint first; uint baseInstance; uint dropped; uint isoCubes; };

uniform vec3 origin;
uniform float cell;
uniform ivec3 nodes;
uniform ivec3 blocks;
uniform float iso;        // in fixed-point density units
uniform uint maxVertices;
uniform bool useList;     // false: every block (no occupancy grid)
uniform uint blockCount;  // without the list: the number of blocks
uniform bool countOnly;   // only find the iso-cubes (the bench times this alone)
const uint kRow = 32768u; // work groups per row of the dispatch (finish.glsl)

int nodeIndex(ivec3 n) { return (n.z * nodes.y + n.y) * nodes.x + n.x; }
float value(ivec3 n) { return float(density[nodeIndex(n)]); }
vec3 gradient(ivec3 n) {
  ivec3 lo = max(n - 1, ivec3(0)), hi = min(n + 1, nodes - 1);
  return vec3(value(ivec3(hi.x, n.y, n.z)) - value(ivec3(lo.x, n.y, n.z)),
              value(ivec3(n.x, hi.y, n.z)) - value(ivec3(n.x, lo.y, n.z)),
              value(ivec3(n.x, n.y, hi.z)) - value(ivec3(n.x, n.y, lo.z)));
}

ivec3 corner[8];
float val[8];

// The point where the iso level crosses edge a–b, from the lower-index node.
void edgePoint(int a, int b, out vec3 p, out vec3 n) {
  if (nodeIndex(corner[b]) < nodeIndex(corner[a])) { int t = a; a = b; b = t; }
  float t = (iso - val[a]) / (val[b] - val[a]);
  vec3 pa = origin + cell * vec3(corner[a]), pb = origin + cell * vec3(corner[b]);
  p = pa + t * (pb - pa);
  n = -mix(gradient(corner[a]), gradient(corner[b]), t);
}

void emit(vec3 p0, vec3 n0, vec3 p1, vec3 n1, vec3 p2, vec3 n2, vec3 inside) {
  // Counter-clockwise seen from outside: the face normal points away from the inside corners.
  if (dot(cross(p1 - p0, p2 - p0), inside - p0) > 0.0) { vec3 t = p1; p1 = p2; p2 = t; t = n1; n1 = n2; n2 = t; }
  uint base = atomicAdd(vertexCount, 3u);
  if (base + 3u > maxVertices) { atomicAdd(vertexCount, uint(-3)); atomicAdd(dropped, 1u); return; }
  vertex[base + 0u] = Vertex(vec4(p0, 1.0), vec4(normalize(n0), 0.0));
  vertex[base + 1u] = Vertex(vec4(p1, 1.0), vec4(normalize(n1), 0.0));
  vertex[base + 2u] = Vertex(vec4(p2, 1.0), vec4(normalize(n2), 0.0));
}

const int tetra[24] = int[24](0, 1, 3, 7,  0, 3, 2, 7,  0, 2, 6, 7,  0, 6, 4, 7,  0, 4, 5, 7,  0, 5, 1, 7);

void main() {
  uint k = gl_WorkGroupID.x + gl_WorkGroupID.y * kRow;
  if (k >= (useList ? count : blockCount)) return;
  uint b = useList ? block[k] : k;
  ivec3 bc = ivec3(int(b) % blocks.x, (int(b) / blocks.x) % blocks.y, int(b) / (blocks.x * blocks.y));
  ivec3 c = bc * 4 + ivec3(gl_LocalInvocationID);
  if (any(greaterThanEqual(c, nodes - 1))) return;
  int inside = 0;
  for (int k = 0; k < 8; ++k) {
    corner[k] = c + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    val[k] = value(corner[k]);
    if (val[k] > iso) ++inside;
  }
  if (inside == 0 || inside == 8) return;
  if (countOnly) { atomicAdd(isoCubes, 1u); return; }
  for (int t = 0; t < 6; ++t) {
    int v[4] = int[4](tetra[4 * t], tetra[4 * t + 1], tetra[4 * t + 2], tetra[4 * t + 3]);
    int in_[4]; int out_[4]; int ni = 0, no = 0;
    for (int k = 0; k < 4; ++k) { if (val[v[k]] > iso) in_[ni++] = v[k]; else out_[no++] = v[k]; }
    if (ni == 0 || ni == 4) continue;
    vec3 centre = vec3(0.0);
    for (int k = 0; k < ni; ++k) centre += origin + cell * vec3(corner[in_[k]]);
    centre /= float(ni);
    vec3 p0, p1, p2, p3, n0, n1, n2, n3;
    if (ni == 1) {
      edgePoint(in_[0], out_[0], p0, n0); edgePoint(in_[0], out_[1], p1, n1); edgePoint(in_[0], out_[2], p2, n2);
      emit(p0, n0, p1, n1, p2, n2, centre);
    } else if (ni == 3) {
      edgePoint(out_[0], in_[0], p0, n0); edgePoint(out_[0], in_[1], p1, n1); edgePoint(out_[0], in_[2], p2, n2);
      emit(p0, n0, p1, n1, p2, n2, centre);
    } else {
      // A quad: in0–out0, in0–out1, in1–out1, in1–out0, split along its first diagonal.
      edgePoint(in_[0], out_[0], p0, n0); edgePoint(in_[0], out_[1], p1, n1);
      edgePoint(in_[1], out_[1], p2, n2); edgePoint(in_[1], out_[0], p3, n3);
      emit(p0, n0, p1, n1, p2, n2, centre);
      emit(p0, n0, p2, n2, p3, n3, centre);
    }
  }
}
