// A shaded sphere impostor on each point sprite. Alpha carries the pixel's coverage of the disc: with
// multisampling, alpha-to-coverage turns it into a smooth rim.
in vec3 splat_color;
in float splat_pixels;

out vec4 frag_color;

void main() {
  float sprite_pixels = splat_pixels + 1.0;
  vec2 p = (gl_PointCoord * 2.0 - 1.0) * (sprite_pixels / splat_pixels);  // 1 on the disc's rim
  float r2 = dot(p, p);
  if (r2 > 1.0 + 2.0 / splat_pixels) discard;
  float edge_pixels = (1.0 - sqrt(r2)) * 0.5 * splat_pixels;  // signed distance to the rim
  vec3 normal = vec3(p.x, -p.y, sqrt(max(1.0 - r2, 0.0)));   // point coordinates run down the sprite
  frag_color = vec4(shade(splat_color, normal, vec3(0.0, 0.0, 1.0)), clamp(edge_pixels + 0.5, 0.0, 1.0));
}
