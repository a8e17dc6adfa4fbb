// Turns each segment into a quad of constant width in pixels (core profile lines are one pixel wide).
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 viewport_size;  // pixels
uniform float width_pixels;

in vec3 line_color_in[];
out vec3 line_color;

void main() {
  vec4 a = gl_in[0].gl_Position;
  vec4 b = gl_in[1].gl_Position;
  if (a.w <= 0.0 || b.w <= 0.0) return;  // a segment reaching behind the eye is left out
  vec2 direction = (b.xy / b.w - a.xy / a.w) * viewport_size;
  if (length(direction) < 1e-6) direction = vec2(1.0, 0.0);
  vec2 offset = normalize(vec2(-direction.y, direction.x)) * width_pixels / viewport_size;
  line_color = line_color_in[0];
  gl_Position = vec4(a.xy + offset * a.w, a.zw);
  EmitVertex();
  gl_Position = vec4(a.xy - offset * a.w, a.zw);
  EmitVertex();
  line_color = line_color_in[1];
  gl_Position = vec4(b.xy + offset * b.w, b.zw);
  EmitVertex();
  gl_Position = vec4(b.xy - offset * b.w, b.zw);
  EmitVertex();
  EndPrimitive();
}
