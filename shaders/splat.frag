// A shaded sphere impostor on each point sprite. With multisampling, alpha carries the pixel's coverage of
// the disc and alpha-to-coverage turns it into a smooth rim; without, the disc is cut at its rim.
in vec3 splat_color;
in float splat_pixels;

uniform int rim_coverage;  // 1: alpha-to-coverage is on

out vec4 frag_color;

void main() {
  float sprite_pixels = splat_pixels + 1.0;
  vec2 p = (gl_PointCoord * 2.0 - 1.0) * (sprite_pixels / splat_pixels);  // 1 on the disc's rim
  float r2 = dot(p, p);
  if (r2 > 1.0 + 2.0 / splat_pixels) discard;
  float edge_pixels = (1.0 - sqrt(r2)) * 0.5 * splat_pixels;  // signed distance to the rim
  vec3 normal = vec3(p.x, -p.y, sqrt(max(1.0 - r2, 0.0)));   // point coordinates run down the sprite
  float coverage = clamp(edge_pixels + 0.5, 0.0, 1.0);
  if (rim_coverage == 0 && coverage < 0.5) discard;
  frag_color = vec4(shade(splat_color, normal, vec3(0.0, 0.0, 1.0)), rim_coverage == 1 ? coverage : 1.0);
}
