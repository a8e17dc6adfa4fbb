#pragma once
/// \file
/// Synthetic categories with parts and ground-truth dense correspondences: the project's embedded default
/// data and the basis of its most precise tests. Every part is a parametric surface S(u, v; shape) with
/// (u, v) in [0, 1]^2, so the same (u, v) is the same semantic point on every instance. Units are metres,
/// y up, front towards -z (as the ShapeNet data). Parameters and ranges: docs/synthetic.md.

#include <cstdint>
#include <string>
#include <vector>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

enum class SyntheticCategory { mug, drill, spray_bottle };

template <>
struct EnumNames<SyntheticCategory> {
  static constexpr const char* what = "synthetic category";
  static constexpr std::array<std::pair<SyntheticCategory, const char*>, 3> table{
      {{SyntheticCategory::mug, "mug"},
       {SyntheticCategory::drill, "drill"},
       {SyntheticCategory::spray_bottle, "spray_bottle"}}};
};

/// Part names in part-index order: mug {body, handle}; drill {base, body, chuck}; spray_bottle {body, neck,
/// trigger}.
std::vector<std::string> part_names(SyntheticCategory category);

struct SyntheticPart {
  std::string name;
  Mesh mesh;  ///< tessellated on a regular (u, v) grid
};

struct SyntheticInstance {
  std::string name;                      ///< e.g. "mug_003"
  std::vector<double> shape_parameters;  ///< the continuous parameters it was drawn from
  std::vector<SyntheticPart> parts;      ///< in part_names() order
};

/// Instance `index` of a category: parameters drawn from a generator seeded with (seed, index).
SyntheticInstance make_synthetic_instance(SyntheticCategory category, std::uint64_t seed, int index);
/// `count` instances, named <category>_000, <category>_001, ...
std::vector<SyntheticInstance> make_synthetic_category(SyntheticCategory category, int count,
                                                       std::uint64_t seed);

/// Ground-truth surface samples: the (u, v) set and part of each row depend only on (category, count, seed),
/// never on the shape, so row i is the same semantic point on every instance.
struct SurfaceSamples {
  Points points;
  Eigen::VectorXi part;
  Eigen::MatrixX2d uv;
};
SurfaceSamples sample_correspondences(SyntheticCategory category, const std::vector<double>& shape_parameters,
                                      int count, std::uint64_t seed);

/// A point of part `part` at (u, v) for the given shape.
Eigen::Vector3d evaluate_surface(SyntheticCategory category, const std::vector<double>& shape_parameters,
                                 int part, double u, double v);

}  // namespace partreg::core
