// Smooth or flat shading, lit from both sides: ShapeNet meshes are open and inconsistently wound, so the
// normal is turned towards the eye. The wireframe pass draws the same triangles as lines in one colour.
in vec3 view_position;
in vec3 view_normal;
in vec3 vertex_color;

uniform int flat_shading;   // 1: face normals from screen-space derivatives
uniform int solid_color;    // 1: wireframe pass, no lighting
uniform vec3 wire_color;

out vec4 frag_color;

void main() {
  if (solid_color == 1) {
    frag_color = vec4(wire_color, 1.0);
    return;
  }
  vec3 to_eye = normalize(-view_position);
  vec3 normal = flat_shading == 1 ? cross(dFdx(view_position), dFdy(view_position)) : view_normal;
  normal = length(normal) > 0.0 ? normalize(normal) : to_eye;
  if (dot(normal, to_eye) < 0.0) normal = -normal;
  frag_color = vec4(shade(vertex_color, normal, to_eye), 1.0);
}
