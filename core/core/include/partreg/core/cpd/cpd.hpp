#pragma once
/// \file
/// Coherent Point Drift (Myronenko & Song 2010): rigid (optionally scaled), affine and non-rigid registration
/// of a source set onto a target set as Gaussian-mixture fitting with EM. See docs/cpd.md for the fast path.
///
/// Units: with `normalize = true` (the default) both sets are mapped by the target's Normalization
/// (bounding-box diagonal 1) before registering, so beta and sigma are in units of the target's diagonal;
/// results come back in the caller's frame. With `normalize = false` coordinates are used as given (training
/// normalises a category once so that every field shares one kernel).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

/// Why an EM loop ended: converged (the tolerance), max_iterations (the settings' cap), polish_limit (the
/// full sets' short stage after the coarse subsets ran its 10 iterations; docs/cpd.md), degenerate.
enum class CpdStopReason { converged, max_iterations, polish_limit, degenerate };
const char* to_string(CpdStopReason reason);

/// Rigid CPD settings.
struct RigidCpdSettings {
  double outlier_weight = 0.1;  ///< w in [0, 1): share of the target explained by uniform noise
  bool estimate_scale = false;  ///< also estimate a uniform scale s
  double tolerance = 1e-6;   ///< stop when the negative log-likelihood changes by less than this, relatively
  int max_iterations = 150;  ///< EM iteration cap
  bool normalize = true;     ///< register in the target's normalised frame (see file comment)
  int threads = 0;           ///< E-step threads; 0 = all cores
  bool exact_e_step = false;  ///< E-step over every pair (the reference); else the fast one (docs/cpd.md)
  double truncation = 1e-4;   ///< fast E-step: kernel values below this are skipped (as non-rigid)
  double cell_size = 0.5;     ///< fast E-step: voxel cell edge in units of sigma (as non-rigid)
  /// Fast E-step: EM first settles on random subsets of this many source and target points (and 8 times
  /// as many, while that is at most half the larger set), then polishes on all of them (at most 10
  /// iterations, docs/cpd.md). No coarse stage when the larger set has fewer than twice this; 0 = never.
  int coarse_points = 1000;
  /// Called after every EM iteration: done = iterations so far, total = max_iterations (bounded: EM usually
  /// converges before), line = sigma2 and the relative change (core/progress.hpp).
  ProgressListener progress;
};

/// Rigid result: target ~ scale * rotation * source + translation.
struct RigidCpdResult {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< caller's units
  double scale = 1.0;
  Points moved;         ///< source after registration, in the target's frame
  double sigma2 = 0.0;  ///< final Gaussian variance (normalised units squared when normalize)
  int iterations = 0;
  CpdStopReason stop_reason = CpdStopReason::max_iterations;
  double seconds = 0.0;
  /// The 4x4 similarity that maps source coordinates into the target frame.
  Eigen::Matrix4d T_target_source() const;
};

/// Affine CPD settings (same meaning as the rigid ones).
struct AffineCpdSettings {
  double outlier_weight = 0.1;  ///< w in [0, 1)
  double tolerance = 1e-6;      ///< relative change of the negative log-likelihood that stops EM
  int max_iterations = 150;     ///< EM iteration cap
  bool normalize = true;        ///< register in the target's normalised frame
  int threads = 0;              ///< E-step threads; 0 = all cores
  bool exact_e_step = false;    ///< E-step over every pair (the reference); else the fast one
  double truncation = 1e-4;     ///< fast E-step: kernel values below this are skipped (as non-rigid)
  double cell_size = 0.5;       ///< fast E-step: voxel cell edge in units of sigma (as non-rigid)
  int coarse_points = 1000;     ///< fast E-step: the first coarse stage's size (as rigid); 0 = none
  /// Called after every EM iteration: done = iterations so far, total = max_iterations (bounded: EM usually
  /// converges before), line = sigma2 and the relative change (core/progress.hpp).
  ProgressListener progress;
};

/// Affine result: target ~ linear * source + translation.
struct AffineCpdResult {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< caller's units
  Points moved;
  double sigma2 = 0.0;
  int iterations = 0;
  CpdStopReason stop_reason = CpdStopReason::max_iterations;
  double seconds = 0.0;
};

/// Non-rigid CPD settings. Lengths in normalised units when normalize is true.
struct NonrigidCpdSettings {
  /// exact: full M x M kernel, a dense solve and an E-step over every pair (the reference);
  /// fast: low-rank kernel (Nystrom eigenpairs) and the fast E-step (cells and truncation, docs/cpd.md);
  /// automatic: fast above 300 source points, exact below.
  enum class Solver { automatic, exact, fast };
  double beta = 2.0;            ///< width of the Gaussian kernel G (normalised length)
  double lambda = 2.0;          ///< weight of the motion-coherence regulariser (unitless)
  double outlier_weight = 0.1;  ///< w in [0, 1)
  double tolerance = 1e-5;      ///< relative change of the negative log-likelihood that stops EM
  int max_iterations = 150;     ///< EM iteration cap
  bool normalize = true;        ///< register in the target's normalised frame
  Solver solver = Solver::automatic;
  int kernel_rank = 0;  ///< eigenpairs of G kept by the fast solver; 0 = chosen from the spectrum
  /// Fast E-step: kernel values below this are skipped (a radius of sqrt(2 ln(1/truncation)) sigma: 4.29
  /// sigma; on a surface the mass left out is about this share of each target point's, docs/cpd.md).
  double truncation = 1e-4;
  /// Fast E-step: points sharing a voxel cell of this edge (in units of sigma) act as one weighted point at
  /// their centroid, so the work while sigma is large follows the cells, not the points. 0 = never merged.
  double cell_size = 0.25;
  /// The exact E-step (every pair, double precision) even with the fast solver's low-rank kernel: the
  /// reference the fast E-step is tested against at sizes where the exact solver's M x M solve is too slow.
  bool exact_e_step = false;
  /// Fast solver: EM first settles on random subsets of this many source and target points (and 8 times
  /// as many, while that is at most half the larger set; lambda scaled by the subset's share of the
  /// target), then polishes on all of them from the subsets' field, which the low-rank kernel carries to
  /// every point (at most 10 iterations, docs/cpd.md). No coarse stage when the larger set has fewer than
  /// twice this; 0 = never.
  int coarse_points = 4000;
  int threads = 0;  ///< E-step threads; 0 = all cores
  /// Called after every EM iteration: done = iterations so far, total = max_iterations (bounded: EM usually
  /// converges before), line = sigma2 and the relative change (core/progress.hpp).
  ProgressListener progress;
};

/// Non-rigid result: moved = source + G(source, source) W, with W in CPD's working frame.
struct NonrigidCpdResult {
  Points moved;                 ///< source after registration, in the caller's frame
  Points weights;               ///< W (M x 3) in the working frame (normalised when normalize was on)
  double beta = 0.0;            ///< kernel width used, working-frame units
  Points source;                ///< the source points, caller's frame
  Normalization normalization;  ///< caller's frame -> working frame (identity when normalize was off)
  double sigma2 = 0.0;          ///< final variance, working-frame units squared
  int iterations = 0;
  CpdStopReason stop_reason = CpdStopReason::max_iterations;
  int kernel_rank = 0;  ///< eigenpairs used (0 for the exact solver)
  double seconds = 0.0;
  /// The learned displacement v(z) = sum_m G(z, c_m) w_m at any points z (caller's frame in and out).
  Points displacement_at(const Points& z) const;
  /// z + v(z): moves any points attached to the source as the source moved.
  Points apply(const Points& z) const { return z + displacement_at(z); }
};

RigidCpdResult register_rigid(const Points& source, const Points& target,
                              const RigidCpdSettings& settings = {});
AffineCpdResult register_affine(const Points& source, const Points& target,
                                const AffineCpdSettings& settings = {});
NonrigidCpdResult register_nonrigid(const Points& source, const Points& target,
                                    const NonrigidCpdSettings& settings = {});

}  // namespace partreg::core
