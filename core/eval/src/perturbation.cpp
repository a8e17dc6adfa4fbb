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
    case Perturbation::none:
      break;
  }
  return {0.0};
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
                  std::uint64_t seed) {
  check_level(kind, level);
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
      // About x, then y, then z, by the same angle with a random sign each, around the box centre.
      const Eigen::Vector3d centre =
          (points.colwise().minCoeff() + points.colwise().maxCoeff()).transpose() / 2;
      Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
      for (int axis = 0; axis < 3; ++axis)
        rotation = Eigen::AngleAxisd(random_sign() * level, Eigen::Vector3d::Unit(axis)) * rotation;
      result.T_perturbed_original.linear() = rotation;
      result.T_perturbed_original.translation() = centre - rotation * centre;
      break;
    }
    case Perturbation::translation: {
      const Eigen::Vector3d shift(random_sign(), random_sign(), random_sign());
      result.T_perturbed_original.translation() = shift * level * diagonal;
      break;
    }
  }
  if (kind == Perturbation::rotation || kind == Perturbation::translation)
    result.points = moved_by(points, result.T_perturbed_original);
  return result;
}

}  // namespace partreg::eval
