#include "partreg/core/geometry/part_selection.hpp"

#include <cmath>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::core {
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& what) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    values.push_back(std::strtod(item.c_str(), &end));
    // strtod reads "nan", "inf" and overflowing literals too: they would travel on as silent garbage.
    if (item.empty() || *end != '\0' || !std::isfinite(values.back()))
      throw UsageError(what + ": '" + item + "' in '" + text + "' is not a finite number");
    if (std::abs(values.back()) > 1e12)
      throw UsageError(what + ": '" + item + "' in '" + text + "' is beyond 1e12, not a sensible size");
  }
  if (values.size() != count)
    throw UsageError(what + " needs " + std::to_string(count) + " comma-separated numbers; '" + text +
                     "' has " + std::to_string(values.size()));
  return values;
}

Eigen::Vector3d parse_vector3(const std::string& text, const std::string& what) {
  const std::vector<double> v = parse_numbers(text, 3, what);
  return {v[0], v[1], v[2]};
}

namespace {

/// "x,y,z" as the user would type it, for messages.
std::string comma_separated(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << v.x() << ',' << v.y() << ',' << v.z();
  return out.str();
}

bool contains(const PartSelector& selector, const Eigen::Vector3d& p) {
  if (const auto* box = std::get_if<BoxSelector>(&selector))
    return (p.array() >= box->min.array()).all() && (p.array() <= box->max.array()).all();
  if (const auto* plane = std::get_if<PlaneSelector>(&selector))
    return (p - plane->point).dot(plane->normal) >= 0.0;
  const auto& sphere = std::get<SphereSelector>(selector);
  return (p - sphere.centre).norm() <= sphere.radius;
}

}  // namespace

PartSelector parse_box(const std::string& text) {
  const auto v = parse_numbers(text, 6, "the box x0,y0,z0,x1,y1,z1");
  const Eigen::Vector3d a(v[0], v[1], v[2]), b(v[3], v[4], v[5]);
  return BoxSelector{a.cwiseMin(b), a.cwiseMax(b)};
}

PartSelector parse_plane(const std::string& text) {
  const auto v = parse_numbers(text, 6, "the plane px,py,pz,nx,ny,nz");
  const Eigen::Vector3d normal(v[3], v[4], v[5]);
  if (normal.norm() == 0.0)
    throw UsageError("the plane's normal " + comma_separated(normal) +
                     " has zero length: it selects no side");
  return PlaneSelector{Eigen::Vector3d(v[0], v[1], v[2]), normal.normalized()};
}

PartSelector parse_sphere(const std::string& text) {
  const auto v = parse_numbers(text, 4, "the sphere cx,cy,cz,r");
  if (!(v[3] > 0.0)) {
    std::ostringstream radius;
    radius << v[3];
    throw UsageError("the sphere's radius " + radius.str() + " is not positive");
  }
  return SphereSelector{Eigen::Vector3d(v[0], v[1], v[2]), v[3]};
}

std::vector<bool> select_points(const Points& points, const PartSelector& selector) {
  std::vector<bool> selected(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    selected[static_cast<std::size_t>(i)] = contains(selector, points.row(i).transpose());
  return selected;
}

std::vector<bool> select_faces(const Mesh& mesh, const PartSelector& selector) {
  std::vector<bool> selected(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d centroid =
        (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
         mesh.vertices.row(mesh.faces(f, 2)))
            .transpose() /
        3.0;
    selected[static_cast<std::size_t>(f)] = contains(selector, centroid);
  }
  return selected;
}

}  // namespace partreg::core
