// Line sets (correspondences, frame triads): widened into screen-space quads by line.geom.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;

uniform mat4 view;
uniform mat4 projection;

out vec3 line_color_in;

void main() {
  gl_Position = projection * (view * vec4(position, 1.0));
  line_color_in = color;
}
