// Shared lighting (prepended to the fragment shaders that shade surfaces). View space: the camera sits at
// the origin looking down -z. A key light above right of the camera, a dimmer fill from the lower left and
// an ambient term, fixed to the camera so every view of a figure is lit alike. Colours are sRGB in [0, 1].

vec3 shade(vec3 base_color, vec3 normal, vec3 to_eye) {
  const vec3 key = normalize(vec3(0.45, 0.6, 1.0));
  const vec3 fill = normalize(vec3(-0.6, -0.35, 0.7));
  float diffuse = 0.62 * max(dot(normal, key), 0.0) + 0.2 * max(dot(normal, fill), 0.0);
  vec3 half_vector = normalize(key + to_eye);
  float specular = 0.16 * pow(max(dot(normal, half_vector), 0.0), 48.0);
  return min(base_color * (0.3 + diffuse) + vec3(specular), vec3(1.0));
}
