#pragma once
/// \file
/// Simple geometric selectors that assign parts without a GUI: a box, a half-space or a ball, in the
/// mesh's own data units and frame. `partreg label` and the GUI's select tools use them.

#include <string>
#include <variant>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core {

struct BoxSelector {
  Eigen::Vector3d min, max;  ///< opposite corners
};
struct PlaneSelector {
  Eigen::Vector3d point, normal;  ///< selects the side the normal points to
};
struct SphereSelector {
  Eigen::Vector3d centre;
  double radius = 0.0;
};
using PartSelector = std::variant<BoxSelector, PlaneSelector, SphereSelector>;

/// `count` comma-separated finite numbers of sensible size (|x| <= 1e12, "0.1,2,-3"); UsageError naming `what`
/// (what the numbers are, or the flag that carried them) for a wrong count or anything else.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& what);
/// Three comma-separated numbers as a point or a direction ("x,y,z").
Eigen::Vector3d parse_vector3(const std::string& text, const std::string& what);

/// Parses "x0,y0,z0,x1,y1,z1" (box), "px,py,pz,nx,ny,nz" (plane) or "cx,cy,cz,r" (sphere); UsageError on
/// a wrong count, a non-number, a zero normal or a non-positive radius. The message names the value, not a
/// command-line flag: a command adds its flag's name, and the app's scripts show the message as it is.
PartSelector parse_box(const std::string& text);
PartSelector parse_plane(const std::string& text);
PartSelector parse_sphere(const std::string& text);

/// Whether each point is selected.
std::vector<bool> select_points(const Points& points, const PartSelector& selector);
/// Whether each face is selected (by its centroid).
std::vector<bool> select_faces(const Mesh& mesh, const PartSelector& selector);

}  // namespace partreg::core
