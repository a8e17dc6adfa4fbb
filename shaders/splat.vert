// Point splats: one GL point per input point, sized so that its disc has the given world radius.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;

uniform mat4 view;
uniform mat4 projection;
uniform float radius;           // world units
uniform float viewport_height;  // pixels

out vec3 splat_color;
out float splat_pixels;  // disc diameter in pixels

void main() {
  gl_Position = projection * (view * vec4(position, 1.0));
  // A length L at clip depth w spans L * projection[1][1] / w of the 2-unit NDC height.
  splat_pixels = max(radius * projection[1][1] * viewport_height / gl_Position.w, 1.0);
  gl_PointSize = splat_pixels + 1.0;  // one pixel of margin for the antialiased rim
  splat_color = color;
}
