#include "cpd_em.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "partreg/core/errors.hpp"

namespace partreg::core::detail {

namespace {

void report_iteration(const EmControl& control, int iteration, double sigma2, double change) {
  std::ostringstream line;
  const int number = control.iteration_offset + iteration;
  line << "iteration " << number << ": sigma2 " << sigma2 << ", relative change " << change;
  const auto cap = static_cast<std::size_t>(control.iteration_offset + control.max_iterations);
  control.progress(Progress{static_cast<std::size_t>(number), cap, line.str(), /*bounded=*/true});
}

}  // namespace

// SQUAREM (Varadhan & Roland 2008, scheme S3) over the moved points. On the drills EM creeps: rigid CPD
// turns by about 1e-3 rad an iteration for 30 iterations, each step a little shorter than the last. Every
// two plain steps from theta0 (to theta1, theta2) this jumps to theta0 - 2 a r + a^2 v, r = theta1 - theta0,
// v = theta2 - 2 theta1 + theta0, a = -|r| / |v| (at most kMaxJump steps' worth); run_em keeps the jump only
// if the likelihood there is no worse than at theta1, else it goes on from theta2. sigma2 is not
// extrapolated: it is EM's annealing, and jumping it ahead (tried) let non-rigid fits skip the gradual
// shrinking that picks their basin (training's held-out mug: hol+part registration error 0.049 of the
// diagonal instead of 0.008).
class Squarem {
 public:
  static constexpr double kMaxJump = 4.0;
  void begin(const Points& moved) {
    start_ = moved;
    steps_ = 0;
  }
  /// After a plain step to `moved` with `sigma2`: true when it moved them to a jump (fallback() holds the
  /// plain step).
  bool after_step(Points& moved, double sigma2) {
    if (++steps_ == 1) {
      first_ = moved;
      return false;
    }
    const Points r = first_ - start_, v = moved - first_ - r;
    const double a = -std::min(kMaxJump, std::sqrt(r.squaredNorm() / std::max(v.squaredNorm(), 1e-300)));
    if (!(a < -1.0)) {  // no longer than the plain steps
      begin(moved);
      return false;
    }
    fallback_ = moved;
    fallback_sigma2_ = sigma2;
    moved = start_ - 2.0 * a * r + a * a * v;
    return true;
  }
  const Points& fallback() const { return fallback_; }
  double fallback_sigma2() const { return fallback_sigma2_; }

 private:
  Points start_, first_, fallback_;
  double fallback_sigma2_ = 0.0;
  int steps_ = 0;
};

EmOutcome run_em(const Points& target, Points& moved, const EmControl& control,
                 const std::function<double(const Expectation&, double sigma2)>& m_step) {
  EmOutcome outcome;
  outcome.stop_reason = control.at_cap;
  double sigma2 = control.initial_sigma2 > 0.0 ? control.initial_sigma2 : initial_sigma2(moved, target);
  if (!(sigma2 > 0.0)) {
    outcome.stop_reason = CpdStopReason::degenerate;
    return outcome;
  }
  double previous = std::numeric_limits<double>::infinity(), previous_edge = -1.0;
  Squarem squarem;
  squarem.begin(moved);
  bool jumped = false;
  int settled = 0;  // consecutive changes under the tolerance
  for (int iteration = 1; iteration <= control.max_iterations; ++iteration) {
    Expectation e = expectation(moved, target, sigma2, control.e_step);
    outcome.iterations = iteration;
    if (jumped && e.cell_edge == previous_edge && e.negative_log_likelihood > previous) {
      moved = squarem.fallback();  // the jump made the fit worse: on from the plain step
      sigma2 = squarem.fallback_sigma2();
      if (++iteration > control.max_iterations) break;
      e = expectation(moved, target, sigma2, control.e_step);
      outcome.iterations = iteration;
    }
    if (!(e.Np > 1e-12)) {  // every target point explained as an outlier: nothing left to fit
      outcome.stop_reason = CpdStopReason::degenerate;
      break;
    }
    sigma2 = m_step(e, sigma2);
    // Relative to |L| + N: the log-likelihood can pass through zero, where a plain relative change explodes.
    // Only likelihoods of the same cells are compared: a new cell size shifts it by its approximation error.
    const double change = e.cell_edge != previous_edge
                              ? std::numeric_limits<double>::infinity()
                              : std::abs(e.negative_log_likelihood - previous) /
                                    (std::abs(e.negative_log_likelihood) + static_cast<double>(target.rows()));
    previous = e.negative_log_likelihood;
    previous_edge = e.cell_edge;
    if (control.progress) report_iteration(control, iteration, sigma2, change);
    if (!(sigma2 > 1e-12)) {  // an exact fit: the variance has nothing left to explain
      sigma2 = 1e-12;
      outcome.stop_reason = CpdStopReason::converged;
      break;
    }
    // Accelerated, a single small change can be the step after a short jump: two in a row are asked for.
    settled = change < control.tolerance ? settled + 1 : 0;
    if (settled >= (control.accelerate ? 2 : 1)) {
      outcome.stop_reason = CpdStopReason::converged;
      break;
    }
    if (control.accelerate) {
      if (jumped) {
        squarem.begin(moved);  // the step after a jump starts the next pair
        jumped = false;
      } else {
        jumped = squarem.after_step(moved, sigma2);
      }
    }
  }
  if (jumped) {  // stopped by the cap after a jump: end on the last step, which the M-step's result matches
    moved = squarem.fallback();
    sigma2 = squarem.fallback_sigma2();
  }
  outcome.sigma2 = sigma2;
  return outcome;
}

// The full sets' stage after coarse ones starts close: a few iterations polish what the subsets found.
constexpr int kFineIterations = 10;

std::vector<CoarseStage> coarse_stages(Eigen::Index sources, Eigen::Index targets, int coarse_points,
                                       bool exact_e_step) {
  std::vector<CoarseStage> stages;
  const Eigen::Index larger = std::max(sources, targets);
  if (exact_e_step || coarse_points <= 0) return stages;
  for (Eigen::Index size = coarse_points; 2 * size <= larger; size *= 8)
    stages.push_back({random_rows(sources, size), random_rows(targets, size)});
  return stages;
}

EmControl next_stage_control(EmControl control, const EmOutcome& previous, bool last) {
  control.initial_sigma2 = previous.sigma2;
  control.iteration_offset += previous.iterations;
  if (last && control.max_iterations > kFineIterations) {  // a stop there is this limit's, not the settings'
    control.max_iterations = kFineIterations;
    control.at_cap = CpdStopReason::polish_limit;
  }
  return control;
}

EmControl run_coarse_stages(const std::vector<CoarseStage>& stages, EmControl control,
                            const std::function<EmOutcome(const CoarseStage&, const EmControl&)>& stage,
                            int& iterations) {
  iterations = 0;
  for (const CoarseStage& rows : stages) {
    const EmOutcome outcome = stage(rows, control);
    if (outcome.stop_reason == CpdStopReason::degenerate) break;
    control = next_stage_control(control, outcome, &rows == &stages.back());
    iterations += outcome.iterations;
  }
  return control;
}

void check_coarse_points(int coarse_points) {
  if (coarse_points != 0 && coarse_points < 50)
    throw UsageError("the CPD coarse stage needs 0 (none) or at least 50 points, got " +
                     std::to_string(coarse_points));
}

std::int64_t now_nanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double seconds_since(std::int64_t start_nanoseconds) {
  return static_cast<double>(now_nanoseconds() - start_nanoseconds) * 1e-9;
}

double nonrigid_variance(const Expectation& e, const Points& target, const Points& moved) {
  const double target_term = (target.array().square().colwise() * e.Pt1.array()).sum();
  const double cross = (e.PX.array() * moved.array()).sum();
  const double moved_term = (moved.array().square().colwise() * e.P1.array()).sum();
  return std::abs(target_term - 2.0 * cross + moved_term) / (3.0 * e.Np);
}

}  // namespace partreg::core::detail
