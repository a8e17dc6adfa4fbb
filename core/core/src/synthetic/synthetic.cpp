#include "partreg/core/synthetic/synthetic.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

constexpr double kTau = 6.283185307179586;
constexpr int kGridU = 48, kGridV = 24;  // tessellation of every part's (u, v) square

// A closed surface of revolution about the y axis: v runs from the bottom pole (0) up the side to the
// top pole (1); `radius(t)` and `height(t)` give the profile for t in [0, 1].
template <class Radius, class Height>
Eigen::Vector3d revolution(double u, double v, const Eigen::Vector3d& base, Radius radius, Height height) {
  double r, y;
  if (v < 0.1) {  // bottom disc
    r = radius(0.0) * v / 0.1, y = height(0.0);
  } else if (v > 0.9) {  // top disc
    r = radius(1.0) * (1.0 - v) / 0.1, y = height(1.0);
  } else {
    const double t = (v - 0.1) / 0.8;
    r = radius(t), y = height(t);
  }
  return base + Eigen::Vector3d(r * std::cos(kTau * u), y, r * std::sin(kTau * u));
}

// A tube of radius `thickness` around the curve centre(u); v goes around it. `normal` is a fixed direction
// not tangent to the curve (the tubes here bend in one plane).
template <class Centre>
Eigen::Vector3d tube(double u, double v, Centre centre, double thickness, const Eigen::Vector3d& normal) {
  const double h = 1e-4;
  const Eigen::Vector3d tangent = (centre(std::min(1.0, u + h)) - centre(std::max(0.0, u - h))).normalized();
  const Eigen::Vector3d side = tangent.cross(normal).normalized(), up = side.cross(tangent);
  // Ends close smoothly: the radius shrinks to 0 over the first and last 5% of u.
  const double taper = std::sqrt(std::clamp(std::min(u, 1.0 - u) / 0.05, 0.0, 1.0));
  return centre(u) + thickness * taper * (std::cos(kTau * v) * side + std::sin(kTau * v) * up);
}

// Parameters: radius, height, taper (top/bottom radius), handle reach, handle height share, handle thickness.
Eigen::Vector3d mug(const std::vector<double>& p, int part, double u, double v) {
  const double radius = p[0], height = p[1], taper = p[2];
  if (part == 0)
    return revolution(
        u, v, Eigen::Vector3d::Zero(), [&](double t) { return radius * (1.0 + (taper - 1.0) * t); },
        [&](double t) { return height * t; });
  const double reach = p[3], span = p[4] * height, thickness = p[5];
  const double mid = 0.55 * height;
  auto centre = [&](double s) {  // a C-shape from the upper to the lower attachment on the +x side
    const double angle = -0.5 * M_PI + M_PI * s;
    return Eigen::Vector3d(radius * (1.0 + (taper - 1.0) * 0.55) - 0.3 * thickness + reach * std::cos(angle),
                           mid - 0.5 * span * std::sin(angle), 0.0);
  };
  return tube(u, v, centre, thickness, Eigen::Vector3d::UnitZ());
}

// Parameters: base width, base depth, grip length, grip tilt, body length, chuck length.
Eigen::Vector3d drill(const std::vector<double>& p, int part, double u, double v) {
  const double base_w = p[0], base_d = p[1], grip = p[2], tilt = p[3], body = p[4], chuck = p[5];
  if (part == 0) {  // base: a rounded box (superellipse cross-section), revolved in u, swept in v
    const double a = kTau * u, t = M_PI * (v - 0.5);
    auto sgnpow = [](double x, double e) { return std::copysign(std::pow(std::abs(x), e), x); };
    return {0.5 * base_w * sgnpow(std::cos(t), 0.4) * sgnpow(std::cos(a), 0.4),
            0.03 * sgnpow(std::sin(t), 0.4) + 0.03,
            0.5 * base_d * sgnpow(std::cos(t), 0.4) * sgnpow(std::sin(a), 0.4)};
  }
  const Eigen::Vector3d grip_top(0.0, 0.06 + grip * std::cos(tilt), grip * std::sin(tilt));
  if (part == 1) {  // body: the grip rising from the base, then the motor housing forward (-z)
    auto centre = [&](double s) -> Eigen::Vector3d {
      if (s < 0.5) return Eigen::Vector3d(0, 0.06, 0) + (s / 0.5) * (grip_top - Eigen::Vector3d(0, 0.06, 0));
      return grip_top + Eigen::Vector3d(0, 0.02, -body * (s - 0.5) / 0.5);
    };
    return tube(u, v, centre, 0.022, Eigen::Vector3d::UnitX());
  }
  const Eigen::Vector3d start = grip_top + Eigen::Vector3d(0, 0.02, -body);
  auto centre = [&](double s) { return Eigen::Vector3d(start + Eigen::Vector3d(0, 0, -chuck * s)); };
  Eigen::Vector3d point = tube(u, v, centre, 0.016, Eigen::Vector3d::UnitX());
  const double cone = 1.0 - 0.5 * u;  // the chuck narrows towards its tip
  return centre(u) + cone * (point - centre(u));
}

// Parameters: body radius, body height, shoulder, neck radius, neck height, trigger length.
Eigen::Vector3d spray_bottle(const std::vector<double>& p, int part, double u, double v) {
  const double radius = p[0], height = p[1], shoulder = p[2], neck_r = p[3], neck_h = p[4], trigger = p[5];
  if (part == 0)
    return revolution(
        u, v, Eigen::Vector3d::Zero(),
        [&](double t) { return t < 0.8 ? radius : radius * (1.0 - shoulder * (t - 0.8) / 0.2); },
        [&](double t) { return height * t; });
  if (part == 1)
    return revolution(
        u, v, Eigen::Vector3d(0, height * 0.98, 0), [&](double) { return neck_r; },
        [&](double t) { return neck_h * t; });
  const Eigen::Vector3d top(0.0, height + 0.8 * neck_h, -neck_r);
  auto centre = [&](double s) {  // forward from the neck, then down: the trigger's lever
    if (s < 0.5) return Eigen::Vector3d(top + Eigen::Vector3d(0, 0, -0.6 * trigger * s / 0.5));
    return Eigen::Vector3d(top + Eigen::Vector3d(0, -trigger * (s - 0.5) / 0.5, -0.6 * trigger));
  };
  return tube(u, v, centre, 0.008, Eigen::Vector3d::UnitX());
}

struct Range {
  double low, high;
};

std::vector<Range> parameter_ranges(SyntheticCategory category) {
  switch (category) {
    case SyntheticCategory::mug:
      return {{0.035, 0.05}, {0.08, 0.12}, {0.85, 1.2}, {0.025, 0.04}, {0.45, 0.7}, {0.006, 0.01}};
    case SyntheticCategory::drill:
      return {{0.06, 0.09}, {0.09, 0.13}, {0.10, 0.14}, {-0.1, 0.25}, {0.12, 0.18}, {0.03, 0.06}};
    case SyntheticCategory::spray_bottle:
      return {{0.035, 0.05}, {0.14, 0.2}, {0.3, 0.6}, {0.012, 0.018}, {0.03, 0.05}, {0.03, 0.05}};
  }
  return {};
}

}  // namespace

std::vector<std::string> part_names(SyntheticCategory category) {
  switch (category) {
    case SyntheticCategory::mug:
      return {"body", "handle"};
    case SyntheticCategory::drill:
      return {"base", "body", "chuck"};
    case SyntheticCategory::spray_bottle:
      return {"body", "neck", "trigger"};
  }
  return {};
}

Eigen::Vector3d evaluate_surface(SyntheticCategory category, const std::vector<double>& p, int part, double u,
                                 double v) {
  if (p.size() != parameter_ranges(category).size()) throw UsageError("wrong number of shape parameters");
  switch (category) {
    case SyntheticCategory::mug:
      return mug(p, part, u, v);
    case SyntheticCategory::drill:
      return drill(p, part, u, v);
    case SyntheticCategory::spray_bottle:
      return spray_bottle(p, part, u, v);
  }
  return Eigen::Vector3d::Zero();
}

SyntheticInstance make_synthetic_instance(SyntheticCategory category, std::uint64_t seed, int index) {
  std::seed_seq sequence{seed, static_cast<std::uint64_t>(index), std::uint64_t{0x5eed}};
  std::mt19937_64 generator(sequence);
  SyntheticInstance instance;
  char name[64];
  std::snprintf(name, sizeof name, "%s_%03d", enum_name(category).c_str(), index);
  instance.name = name;
  for (const Range& range : parameter_ranges(category))
    instance.shape_parameters.push_back(
        std::uniform_real_distribution<double>(range.low, range.high)(generator));
  const auto names = part_names(category);
  for (int part = 0; part < static_cast<int>(names.size()); ++part) {
    SyntheticPart out{names[static_cast<std::size_t>(part)], {}};
    out.mesh.vertices.resize((kGridU + 1) * (kGridV + 1), 3);
    for (int i = 0; i <= kGridU; ++i)
      for (int j = 0; j <= kGridV; ++j)
        out.mesh.vertices.row(i * (kGridV + 1) + j) =
            evaluate_surface(category, instance.shape_parameters, part, static_cast<double>(i) / kGridU,
                             static_cast<double>(j) / kGridV);
    out.mesh.faces.resize(2 * kGridU * kGridV, 3);
    int f = 0;
    for (int i = 0; i < kGridU; ++i)
      for (int j = 0; j < kGridV; ++j) {
        const int a = i * (kGridV + 1) + j, b = a + kGridV + 1;
        out.mesh.faces.row(f++) << a, a + 1, b;
        out.mesh.faces.row(f++) << b, a + 1, b + 1;
      }
    instance.parts.push_back(std::move(out));
  }
  return instance;
}

std::vector<SyntheticInstance> make_synthetic_category(SyntheticCategory category, int count,
                                                       std::uint64_t seed) {
  if (count < 1) throw UsageError("a synthetic category needs at least one instance");
  std::vector<SyntheticInstance> instances;
  for (int i = 0; i < count; ++i) instances.push_back(make_synthetic_instance(category, seed, i));
  return instances;
}

SurfaceSamples sample_correspondences(SyntheticCategory category, const std::vector<double>& shape_parameters,
                                      int count, std::uint64_t seed) {
  if (count < 1) throw UsageError("asked for no correspondence samples");
  const int parts = static_cast<int>(part_names(category).size());
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SurfaceSamples samples;
  samples.points.resize(count, 3);
  samples.part.resize(count);
  samples.uv.resize(count, 2);
  for (int i = 0; i < count; ++i) {
    const int part = i % parts;  // equal shares per part, fixed by the row index
    const double u = uniform(generator), v = uniform(generator);
    samples.part[i] = part;
    samples.uv.row(i) << u, v;
    samples.points.row(i) = evaluate_surface(category, shape_parameters, part, u, v);
  }
  return samples;
}

}  // namespace partreg::core
