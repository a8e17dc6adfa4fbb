#pragma once
/// \file
/// The paper's perturbations of an observation (section 4): Gaussian noise, outliers uniform in the
/// bounding box, rotation about x, y and z by the same angle (each with a random sign), translation along
/// all three axes. Lengths are given relative to the object's bounding-box diagonal so one set of levels
/// fits every category; the paper's levels (for objects of about 0.3 m) are the defaults.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "partreg/core/enum_names.hpp"
#include "partreg/core/types.hpp"

namespace partreg::eval {

enum class Perturbation { none, noise, outliers, rotation, translation };

}  // namespace partreg::eval

template <>
struct partreg::core::EnumNames<partreg::eval::Perturbation> {
  using P = partreg::eval::Perturbation;
  static constexpr const char* what = "perturbation";
  static constexpr std::array<std::pair<P, const char*>, 5> table{{{P::none, "none"},
                                                                   {P::noise, "noise"},
                                                                   {P::outliers, "outliers"},
                                                                   {P::rotation, "rotation"},
                                                                   {P::translation, "translation"}}};
};

namespace partreg::eval {

/// The four kinds the robustness sweeps use, in the paper's order.
const std::vector<Perturbation>& sweep_kinds();

/// The object size the paper's absolute levels refer to: its objects are about 0.3 m across (diagonal).
constexpr double kPaperDiagonal = 0.3;

/// The paper's five levels of a kind in its own units: noise sigma 0.005..0.025 m, outlier ratio 0.04..0.2,
/// rotation 0.13..0.65 rad, translation 0.02..0.1 m.
std::vector<double> paper_levels(Perturbation kind);

/// Whether a level of this kind is a length (noise, translation) and so scales with the object's size.
bool is_length(Perturbation kind);

/// A level in the units `perturb` takes: lengths relative to the diagonal (paper level / 0.3 m), ratios and
/// angles unchanged.
double relative_level(Perturbation kind, double paper_level);

/// An observation after a perturbation.
struct Perturbed {
  core::Points points;
  /// Rigid motion applied to the object (identity for noise and outliers): the ground truth moves with it.
  Eigen::Isometry3d T_perturbed_original = Eigen::Isometry3d::Identity();
};

/// `points` moved by the rigid motion T (one point per row).
core::Points moved_by(const core::Points& points, const Eigen::Isometry3d& T);

/// Applies `kind` at `level` (lengths as a fraction of `diagonal`, the object's bounding-box diagonal in data
/// units; outliers as a ratio of added to present points; rotation in radians, about the centre of the
/// points' bounding box). Deterministic for a seed. UsageError for a negative or non-finite level, an outlier
/// ratio above 10 or a rotation above pi.
Perturbed perturb(const core::Points& points, Perturbation kind, double level, double diagonal,
                  std::uint64_t seed);

}  // namespace partreg::eval
