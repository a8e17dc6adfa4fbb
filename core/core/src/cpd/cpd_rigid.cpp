// Rigid and affine CPD (Myronenko & Song 2010, Figs. 2 and 3): closed-form M-steps on the E-step's sums.
#include <Eigen/SVD>

#include "cpd_em.hpp"
#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core {
namespace {

// Weighted centroids and the centred cross term A = X^T P^T Y - Np mu_x mu_y^T shared by both M-steps.
struct Moments {
  Eigen::Vector3d mu_target, mu_source;
  Eigen::Matrix3d cross;         ///< sum_mn P_mn xhat_n yhat_m^T
  double source_spread = 0.0;    ///< tr(Yhat^T d(P1) Yhat)
  Eigen::Matrix3d source_outer;  ///< Yhat^T d(P1) Yhat
  double target_spread = 0.0;    ///< tr(Xhat^T d(Pt1) Xhat)
};

Moments moments(const detail::Expectation& e, const Points& source, const Points& target) {
  Moments m;
  m.mu_target = (target.transpose() * e.Pt1) / e.Np;
  m.mu_source = (source.transpose() * e.P1) / e.Np;
  m.cross = e.PX.transpose() * source - e.Np * m.mu_target * m.mu_source.transpose();
  const Points source_centred = source.rowwise() - m.mu_source.transpose();
  const Points target_centred = target.rowwise() - m.mu_target.transpose();
  m.source_outer = source_centred.transpose() * e.P1.asDiagonal() * source_centred;
  m.source_spread = m.source_outer.trace();
  m.target_spread = (target_centred.array().square().colwise() * e.Pt1.array()).sum();
  return m;
}

template <typename Settings>
detail::EmControl control_of(const Settings& settings) {
  detail::EmControl control;
  control.e_step.outlier_weight = settings.outlier_weight;
  control.e_step.threads = settings.threads;
  control.e_step.exact = settings.exact_e_step;
  control.accelerate = !control.e_step.exact;
  control.e_step.truncation = settings.truncation;
  control.e_step.cell_size = settings.cell_size;
  control.tolerance = settings.tolerance;
  control.max_iterations = settings.max_iterations;
  control.progress = settings.progress;
  return control;
}

// Frames of the working (normalised) space and the caller's space: x = k x' + c.
Normalization working_frame(const Points& target, bool normalize) {
  return normalize ? Normalization::fit(target) : Normalization{};
}

Points moved_by(const RigidCpdResult& r, const Points& source) {
  return (r.scale * source * r.rotation.transpose()).rowwise() + r.translation.transpose();
}

Points moved_by(const AffineCpdResult& r, const Points& source) {
  return (source * r.linear.transpose()).rowwise() + r.translation.transpose();
}

// Shared by rigid and affine CPD: validate, move both sets into the working frame, run EM with `m_step`
// (which sets the result's transform from the E-step's sums and returns sigma2), and fill the result's
// common fields in the caller's frame. Seven or twelve numbers are carried by a few hundred points, so EM
// first settles on a random subset (coarse_points) and then polishes on every point (docs/cpd.md).
// Returns the working frame so the caller can map its transform back.
template <typename Settings, typename Result, typename MStep>
Normalization run_linear_cpd(const Points& source_in, const Points& target_in, const Settings& settings,
                             Result& result, MStep m_step) {
  const auto start = detail::now_nanoseconds();
  detail::check_cpd_points(source_in, "source");
  detail::check_cpd_points(target_in, "target");
  detail::check_cpd_common(settings.outlier_weight, settings.tolerance, settings.max_iterations);
  detail::check_fast_e_step(settings.truncation, settings.cell_size);
  detail::check_coarse_points(settings.coarse_points);
  const Normalization frame = working_frame(target_in, settings.normalize);
  const Points source = frame.apply(source_in), target = frame.apply(target_in);
  const auto stage = [&](const Points& stage_source, const Points& stage_target, Points& moved,
                         const detail::EmControl& control) {
    return detail::run_em(stage_target, moved, control, [&](const detail::Expectation& e, double) {
      const double sigma2 = m_step(e, stage_source, stage_target, result);
      moved = moved_by(result, stage_source);
      return sigma2;
    });
  };
  // Coarse to fine: each stage starts from the transform the one before found.
  int iterations = 0;
  bool started = false;  // a stage completed: the next starts from its transform
  const detail::EmControl control = detail::run_coarse_stages(
      detail::coarse_stages(source.rows(), target.rows(), settings.coarse_points, settings.exact_e_step),
      control_of(settings),
      [&](const detail::CoarseStage& rows, const detail::EmControl& stage_control) {
        const Points stage_source = select_rows(source, rows.source);
        Points stage_moved = started ? moved_by(result, stage_source) : stage_source;
        const auto outcome =
            stage(stage_source, select_rows(target, rows.target), stage_moved, stage_control);
        started = started || outcome.stop_reason != CpdStopReason::degenerate;
        return outcome;
      },
      iterations);
  Points moved = started ? moved_by(result, source) : source;
  const auto outcome = stage(source, target, moved, control);
  result.moved = frame.undo(moved);
  result.sigma2 = outcome.sigma2;
  result.iterations = iterations + outcome.iterations;
  result.stop_reason = outcome.stop_reason;
  result.seconds = detail::seconds_since(start);
  return frame;
}

}  // namespace

const char* to_string(CpdStopReason reason) {
  switch (reason) {
    case CpdStopReason::converged:
      return "converged";
    case CpdStopReason::max_iterations:
      return "max_iterations";
    case CpdStopReason::polish_limit:
      return "polish_limit";
    case CpdStopReason::degenerate:
      return "degenerate";
  }
  return "unknown";
}

Eigen::Matrix4d RigidCpdResult::T_target_source() const {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  transform.topLeftCorner<3, 3>() = scale * rotation;
  transform.topRightCorner<3, 1>() = translation;
  return transform;
}

RigidCpdResult register_rigid(const Points& source_in, const Points& target_in,
                              const RigidCpdSettings& settings) {
  RigidCpdResult result;
  const Normalization frame = run_linear_cpd(
      source_in, target_in, settings, result,
      [&](const detail::Expectation& e, const Points& source, const Points& target, RigidCpdResult& r) {
        const Moments m = moments(e, source, target);
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m.cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
        Eigen::Vector3d reflection_guard(1.0, 1.0, (svd.matrixU() * svd.matrixV().transpose()).determinant());
        r.rotation = svd.matrixU() * reflection_guard.asDiagonal() * svd.matrixV().transpose();
        const double trace = (m.cross.transpose() * r.rotation).trace();
        r.scale = settings.estimate_scale ? trace / m.source_spread : 1.0;
        r.translation = m.mu_target - r.scale * r.rotation * m.mu_source;
        const double explained = settings.estimate_scale ? r.scale * trace : 2.0 * trace - m.source_spread;
        return std::abs(m.target_spread - explained) / (3.0 * e.Np);
      });
  // Back to the caller's frame: x = k x' + c with x' = s R y' + t' and y' = (y - c) / k.
  result.translation =
      frame.scale * result.translation + frame.centre - result.scale * result.rotation * frame.centre;
  return result;
}

AffineCpdResult register_affine(const Points& source_in, const Points& target_in,
                                const AffineCpdSettings& settings) {
  AffineCpdResult result;
  const Normalization frame = run_linear_cpd(
      source_in, target_in, settings, result,
      [&](const detail::Expectation& e, const Points& source, const Points& target, AffineCpdResult& r) {
        const Moments m = moments(e, source, target);
        r.linear = m.cross * m.source_outer.inverse();
        r.translation = m.mu_target - r.linear * m.mu_source;
        return std::abs(m.target_spread - (m.cross * r.linear.transpose()).trace()) / (3.0 * e.Np);
      });
  result.translation = frame.scale * result.translation + frame.centre - result.linear * frame.centre;
  return result;
}

}  // namespace partreg::core
