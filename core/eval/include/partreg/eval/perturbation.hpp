#pragma once
/// \file
/// The paper's perturbations of an observation (section 4): Gaussian noise, outliers uniform in the
/// bounding box, rotation about x, y and z by the same angle (each with a random sign), translation along
/// all three axes; and one the paper lacks: a yaw about the category's up axis after a small tilt (a mug
/// met at any heading). Lengths are given relative to the object's bounding-box diagonal so one set of levels
/// fits every category; the paper's levels (for objects of about 0.3 m) are the defaults.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/types.hpp"

namespace partreg::eval {

enum class Perturbation { none, noise, outliers, rotation, translation, yaw };

}  // namespace partreg::eval

template <>
struct partreg::core::EnumNames<partreg::eval::Perturbation> {
  using P = partreg::eval::Perturbation;
  static constexpr const char* what = "perturbation";
  static constexpr std::array<std::pair<P, const char*>, 6> table{{{P::none, "none"},
                                                                   {P::noise, "noise"},
                                                                   {P::outliers, "outliers"},
                                                                   {P::rotation, "rotation"},
                                                                   {P::translation, "translation"},
                                                                   {P::yaw, "yaw"}}};
};

namespace partreg::eval {

/// The four kinds the paper's robustness sweeps use, in its order.
const std::vector<Perturbation>& sweep_kinds();

/// Every kind a sweep can use: the paper's four, then yaw.
const std::vector<Perturbation>& all_sweep_kinds();

/// The object size the paper's absolute levels refer to: its objects are about 0.3 m across (diagonal).
constexpr double kPaperDiagonal = 0.3;

/// The paper's five levels of a kind in its own units: noise sigma 0.005..0.025 m, outlier ratio 0.04..0.2,
/// rotation 0.13..0.65 rad, translation 0.02..0.1 m.
std::vector<double> paper_levels(Perturbation kind);

/// Every level a sweep of this kind can run, by level index: the paper's five first (for rotation then the
/// wide levels past the paper's 0.65 rad, up to pi/2: 0.78, 0.91, 1.05, 1.31, 1.57 rad); yaw: 0 to 330
/// degrees in 30 degree steps (in radians).
const std::vector<double>& sweep_levels(Perturbation kind);

/// Of sweep_levels(rotation), the index of the first wide level (past the paper's five).
constexpr int kFirstWideRotationLevel = 5;

/// The tilt of the up axis before a yaw, about a horizontal axis drawn at random (radians): a robot seldom
/// meets an object exactly upright.
constexpr double kYawTilt = 0.1;

/// A level as tables and plots show it: yaw in degrees, the rest in the paper's units.
double shown_level(Perturbation kind, double level);

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
/// units; outliers as a ratio of added to present points; rotation and yaw in radians, about the centre of
/// the points' bounding box; yaw turns about `up`, the category's up axis, after a tilt of kYawTilt).
/// Deterministic for a seed. UsageError for a negative or non-finite level, an outlier ratio above 10, a
/// rotation above pi, a yaw of 2 pi or more or an up axis of zero length.
Perturbed perturb(const core::Points& points, Perturbation kind, double level, double diagonal,
                  std::uint64_t seed, const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());

}  // namespace partreg::eval
