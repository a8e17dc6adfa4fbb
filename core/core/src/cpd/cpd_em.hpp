#pragma once
// The EM loop shared by rigid, affine and non-rigid CPD (internal to partreg_core): E-step, the variant's
// M-step, SQUAREM's jumps where they help, and the coarse stages on random subsets before the full sets.

#include <cstdint>
#include <functional>

#include "cpd_expectation.hpp"
#include "partreg/core/cpd/cpd.hpp"

namespace partreg::core::detail {

/// What every CPD variant's EM loop needs to know.
struct EmControl {
  EStepSettings e_step;
  double tolerance = 1e-6;
  int max_iterations = 150;
  ProgressListener progress;  ///< after every iteration (the settings' own listener)
  /// The starting variance; 0 = the classic all-pairs value (initial_sigma2). A start that is already close
  /// (the refinement after a space fit) gives its own residual variance instead.
  double initial_sigma2 = 0.0;
  /// SQUAREM steps between pairs of EM steps (docs/cpd.md): rigid and affine fast paths set it.
  bool accelerate = false;
  int iteration_offset = 0;  ///< added to the iteration numbers reported (a second stage continues the count)
  CpdStopReason at_cap = CpdStopReason::max_iterations;  ///< the stop reason when max_iterations ran out
};

struct EmOutcome {
  double sigma2 = 0.0;
  int iterations = 0;
  CpdStopReason stop_reason = CpdStopReason::max_iterations;
};

/// The EM loop: E-step on `moved`, then `m_step` (which updates `moved` and returns the new sigma2),
/// until the negative log-likelihood settles, sigma2 collapses, or the cap is hit.
EmOutcome run_em(const Points& target, Points& moved, const EmControl& control,
                 const std::function<double(const Expectation&, double sigma2)>& m_step);

/// Coarse-to-fine EM (docs/cpd.md): the rows of the source and target one coarse stage runs on.
struct CoarseStage {
  std::vector<int> source, target;
};

/// The coarse stages before the full sets, smallest first: random subsets of coarse_points, 8 times as
/// many, ... while a stage holds at most half of the larger set (so none for sets under twice
/// coarse_points), and none with the exact E-step or coarse_points 0. Each stage's rows include the last's.
std::vector<CoarseStage> coarse_stages(Eigen::Index sources, Eigen::Index targets, int coarse_points,
                                       bool exact_e_step);

/// The control of the stage after one that ended with `previous`: it starts from that variance and
/// continues the iteration count; the full sets' stage (`last`) runs at most kFineIterations.
EmControl next_stage_control(EmControl control, const EmOutcome& previous, bool last);

/// Runs the coarse stages in turn, smallest first: `stage(rows, control)` runs EM on one, starting from the
/// last one's result, and returns its outcome. Each next stage's control continues the last's
/// (next_stage_control); a degenerate stage ends them, and the full sets go on from the last good result.
/// Returns the control for the full sets; `iterations` gets the iterations of the stages that completed.
EmControl run_coarse_stages(const std::vector<CoarseStage>& stages, EmControl control,
                            const std::function<EmOutcome(const CoarseStage&, const EmControl&)>& stage,
                            int& iterations);

/// Validates the coarse stage's size (0 = none, else at least 50 points).
void check_coarse_points(int coarse_points);

/// The seconds elapsed since `start` (a steady_clock time point in nanoseconds since its epoch).
double seconds_since(std::int64_t start_nanoseconds);
std::int64_t now_nanoseconds();

}  // namespace partreg::core::detail
