// The water surface from marching tetrahedra: the vertex buffer the compute pass filled.
layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
uniform mat4 clipFromWorld;
out vec3 worldPos;
out vec3 worldNormal;
void main() {
  worldPos = position.xyz;
  worldNormal = normal.xyz;
  gl_Position = clipFromWorld * position;
}
