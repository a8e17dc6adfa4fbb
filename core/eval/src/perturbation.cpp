#include "partreg/eval/perturbation.hpp"

#include <cmath>
#include <random>

#include "partreg/core/errors.hpp"

namespace partreg::eval {

const std::vector<Perturbation>& sweep_kinds() {
  static const std::vector<Perturbation> kinds = {Perturbation::noise, Perturbation::outliers,
                                                  Perturbation::rotation, Perturbation::translation};
  return kinds;
}

const std::vector<Perturbation>& all_sweep_kinds() {
  static const std::vector<Perturbation> kinds = {Perturbation::noise, Perturbation::outliers,
                                                  Perturbation::rotation, Perturbation::translation,
                                                  Perturbation::yaw};
  return kinds;
}

const std::vector<double>& sweep_levels(Perturbation kind) {
  static const std::vector<double> noise = paper_levels(Perturbation::noise),
                                   outliers = paper_levels(Perturbation::outliers),
                                   translation = paper_levels(Perturbation::translation), none = {0.0};
  // Wide rotation stops at pi/2: turns about x, y and z by the same larger angle fold back (at pi they
  // compose to the identity).
  static const std::vector<double> rotation = [] {
    std::vector<double> levels = paper_levels(Perturbation::rotation);
    for (double wide : {0.78, 0.91, 1.05, 1.31, 1.57}) levels.push_back(wide);
    return levels;
  }();
  static const std::vector<double> yaw = [] {
    std::vector<double> levels;
    for (int degrees = 0; degrees < 360; degrees += 30) levels.push_back(degrees * M_PI / 180.0);
    return levels;
  }();
  switch (kind) {
    case Perturbation::noise:
      return noise;
    case Perturbation::outliers:
      return outliers;
    case Perturbation::rotation:
      return rotation;
    case Perturbation::translation:
      return translation;
    case Perturbation::yaw:
      return yaw;
    case Perturbation::none:
      break;
  }
  return none;
}

std::vector<double> paper_levels(Perturbation kind) {
  switch (kind) {
    case Perturbation::noise:
      return {0.005, 0.01, 0.015, 0.02, 0.025};
    case Perturbation::outliers:
      return {0.04, 0.08, 0.12, 0.16, 0.2};
    case Perturbation::rotation:
      return {0.13, 0.26, 0.39, 0.52, 0.65};
    case Perturbation::translation:
      return {0.02, 0.04, 0.06, 0.08, 0.1};
    case Perturbation::yaw:  // not the paper's: see sweep_levels
    case Perturbation::none:
      break;
  }
  return {0.0};
}

double shown_level(Perturbation kind, double level) {
  return kind == Perturbation::yaw ? level * 180.0 / M_PI : level;
}

bool is_length(Perturbation kind) { return kind == Perturbation::noise || kind == Perturbation::translation; }

double relative_level(Perturbation kind, double paper_level) {
  return is_length(kind) ? paper_level / kPaperDiagonal : paper_level;
}

namespace {

void check_level(Perturbation kind, double level) {
  if (!std::isfinite(level) || level < 0)
    throw UsageError(core::enum_name(kind) + " level must be a finite number >= 0, not " +
                     std::to_string(level));
  if (kind == Perturbation::outliers && level > 10)
    throw UsageError("outlier ratio " + std::to_string(level) + " is out of range (0 to 10)");
  if (kind == Perturbation::rotation && level > M_PI)
    throw UsageError("rotation " + std::to_string(level) + " rad is out of range (0 to pi)");
  if (kind == Perturbation::yaw && level >= 2 * M_PI)
    throw UsageError("yaw " + std::to_string(level) + " rad is out of range (0 to 2 pi)");
}

// A rigid turn by `rotation` about the centre of the points' bounding box.
Eigen::Isometry3d turn_about_centre(const core::Points& points, const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d centre = (points.colwise().minCoeff() + points.colwise().maxCoeff()).transpose() / 2;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation;
  T.translation() = centre - rotation * centre;
  return T;
}

core::Points add_outliers(const core::Points& points, double ratio, std::mt19937_64& random) {
  const Eigen::RowVector3d low = points.colwise().minCoeff(), high = points.colwise().maxCoeff();
  const auto count = static_cast<Eigen::Index>(std::llround(ratio * double(points.rows())));
  core::Points out(points.rows() + count, 3);
  out.topRows(points.rows()) = points;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Eigen::Index i = points.rows(); i < out.rows(); ++i)
    for (int k = 0; k < 3; ++k) out(i, k) = low[k] + unit(random) * (high[k] - low[k]);
  return out;
}

}  // namespace

core::Points moved_by(const core::Points& points, const Eigen::Isometry3d& T) {
  return (points * T.linear().transpose()).rowwise() + T.translation().transpose();
}

Perturbed perturb(const core::Points& points, Perturbation kind, double level, double diagonal,
                  std::uint64_t seed, const Eigen::Vector3d& up) {
  check_level(kind, level);
  if (!(up.norm() > 1e-12) || !up.allFinite()) throw UsageError("the up axis of a yaw must have a length");
  std::mt19937_64 random(seed);
  Perturbed result{points, Eigen::Isometry3d::Identity()};
  if (points.rows() == 0) return result;
  auto random_sign = [&random] { return std::bernoulli_distribution(0.5)(random) ? 1.0 : -1.0; };
  switch (kind) {
    case Perturbation::none:
      break;
    case Perturbation::noise: {
      std::normal_distribution<double> gaussian(0.0, level * diagonal);
      for (Eigen::Index i = 0; i < result.points.size(); ++i) result.points.data()[i] += gaussian(random);
      break;
    }
    case Perturbation::outliers:
      result.points = add_outliers(points, level, random);
      break;
    case Perturbation::rotation: {
      // About x, then y, then z, by the same angle with a random sign each.
      Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
      for (int axis = 0; axis < 3; ++axis)
        rotation = Eigen::AngleAxisd(random_sign() * level, Eigen::Vector3d::Unit(axis)) * rotation;
      result.T_perturbed_original = turn_about_centre(points, rotation);
      break;
    }
    case Perturbation::yaw: {
      const Eigen::Vector3d axis = up.normalized(), across = axis.unitOrthogonal();
      const double heading = std::uniform_real_distribution<double>(0.0, 2 * M_PI)(random);
      const Eigen::Vector3d tilt_axis = Eigen::AngleAxisd(heading, axis) * across;
      const Eigen::Matrix3d rotation =
          Eigen::AngleAxisd(kYawTilt, tilt_axis).toRotationMatrix() * Eigen::AngleAxisd(level, axis);
      result.T_perturbed_original = turn_about_centre(points, rotation);
      break;
    }
    case Perturbation::translation: {
      const Eigen::Vector3d shift(random_sign(), random_sign(), random_sign());
      result.T_perturbed_original.translation() = shift * level * diagonal;
      break;
    }
  }
  if (kind == Perturbation::rotation || kind == Perturbation::translation || kind == Perturbation::yaw)
    result.points = moved_by(points, result.T_perturbed_original);
  return result;
}

}  // namespace partreg::eval
