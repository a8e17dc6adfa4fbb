#pragma once
/// \file
/// Category-level registration (paper, section 3.2): find the latent vector x of a shape space and a rigid
/// pose that bring the deformed canonical C + G W(x) onto an observed cloud (Eq. 3), with Ceres.
/// Variants: holistic (one space), partwise (every part in its own space, independently, in parallel) and
/// hol+part (holistic first; its pose and, projected into each part's space, its deformation initialise the
/// parts). Choices and the measurements behind the defaults: docs/registration.md.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/category_model.hpp"

namespace partreg::core {

enum class Variant { holistic, partwise, hol_part };
/// Which closest points the objective sums over.
enum class Direction {
  canonical_to_observed,  ///< the paper's Eq. 3: every canonical point to its closest observed point
  observed_to_canonical,  ///< every observed point to its closest deformed canonical point
  symmetric               ///< both, each normalised by its point count
};
enum class Loss { squared, huber, cauchy, trimmed };

Variant parse_variant(
    const std::string& name);  ///< "holistic" | "partwise" | "hol+part"; UsageError otherwise
std::string to_string(Variant variant);
Direction parse_direction(const std::string& name);  ///< "canonical" | "observed" | "symmetric"
Loss parse_loss(const std::string& name);            ///< "squared" | "huber" | "cauchy" | "trimmed"
std::string to_string(Direction direction);          ///< the name parse_direction reads
std::string to_string(Loss loss);                    ///< the name parse_loss reads

/// Registration settings. Lengths are in normalised units (the model's canonical diagonal is 1).
struct RegistrationSettings {
  Variant variant = Variant::holistic;
  Direction direction =
      Direction::observed_to_canonical;  ///< measured best on partial views: docs/registration.md
  Loss loss = Loss::huber;
  double loss_scale = 0.02;     ///< Huber/Cauchy scale (normalised length)
  double trim_fraction = 0.1;   ///< trimmed loss: share of the worst correspondences dropped each step
  double prior_weight = 1e-4;   ///< weight of the Gaussian prior sum_k x_k^2 / var_k against the data term
  bool estimate_scale = false;  ///< also fit a uniform scale
  std::optional<Eigen::Vector3d>
      viewpoint;                      ///< observed frame, data units: only canonical points facing it count
  bool align_principal_axes = false;  ///< start from the 4 rotations aligning principal axes (poses far off)
  int restarts = 1;                   ///< initial rotations tried about the up axis (the lowest cost wins)
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();  ///< the category's up axis (canonical frame)
  int outer_iterations = 25;                      ///< correspondence refreshes
  int inner_iterations = 4;                       ///< Ceres iterations per refresh
  double tolerance = 1e-5;     ///< stop when the cost changes by less than this, relatively
  int observed_points = 2000;  ///< farthest-point subset of the observation matched each step (measured)
};

/// The fit of one space.
struct SpaceFit {
  std::string space;
  Eigen::VectorXd latent;
  Eigen::Matrix4d T_observed_canonical =
      Eigen::Matrix4d::Identity();  ///< canonical data frame -> observed frame
  double scale = 1.0;
  double cost = 0.0;
  int iterations = 0;
  double seconds = 0.0;
};

/// The state after one outer step, for stepping through a registration.
struct HistoryStep {
  std::string space;
  Eigen::VectorXd latent;
  Eigen::Matrix4d T_observed_canonical = Eigen::Matrix4d::Identity();
  double cost = 0.0;
  double seconds = 0.0;  ///< since the start of this space's registration
};

/// How well the result fits the observation: closest-point distances from the deformed canonical points.
struct FitStatistics {
  double mean = 0.0, p90 = 0.0;                        ///< data units
  double mean_normalised = 0.0, p90_normalised = 0.0;  ///< divided by the model's diagonal
};

struct RegistrationResult {
  Variant variant = Variant::holistic;
  std::vector<SpaceFit> fits;        ///< holistic first where it ran, then the parts
  Points deformed;                   ///< deformed canonical points in the observed frame (data units)
  Eigen::VectorXi part;              ///< part per deformed point
  std::vector<HistoryStep> history;  ///< every outer step of every space, in order
  FitStatistics fit;
  double seconds = 0.0;
};

/// Registers `model` to `observed` (data units, any frame near the category's). Throws InputError for fewer
/// than 10 finite points or an observation wildly out of scale with the model; UsageError for a part-based
/// variant on a model without parts.
RegistrationResult register_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings = {});

}  // namespace partreg::core
