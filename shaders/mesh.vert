// Triangle meshes with per-vertex colour and (for smooth shading) per-vertex normals.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;

uniform mat4 view;
uniform mat4 projection;

out vec3 view_position;
out vec3 view_normal;
out vec3 vertex_color;

void main() {
  vec4 p = view * vec4(position, 1.0);
  view_position = p.xyz;
  view_normal = mat3(view) * normal;  // the view matrix is a rotation plus a translation
  vertex_color = color;
  gl_Position = projection * p;
}
