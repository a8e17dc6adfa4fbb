#pragma once
/// \file
/// Training a category (paper, section 3.1): choose a canonical instance, register it with non-rigid CPD to
/// every other instance, propagate part labels through those registrations, and learn one holistic and one
/// per-part shape space with PCA-EM. Inputs are plain point sets: reading dataset folders is partreg_io's
/// job.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::core {

/// One aligned training instance, in the category's data frame.
struct TrainingInstance {
  std::string name;
  Points points;         ///< a dense, roughly uniform sample of the surface (data units)
  Eigen::VectorXi part;  ///< part index per point from the instance's own part files; empty if it has none
  Mesh mesh;             ///< its surface (data units); may be empty for cloud data
  Eigen::VectorXi mesh_vertex_part;  ///< part per mesh vertex (empty if the mesh or the parts are absent)
};

/// Training settings. Lengths are in normalised units: the canonical's bounding-box diagonal is 1.
struct TrainingSettings {
  int canonical_points =
      1000;                  ///< M, canonical points kept by farthest-point sampling (clamped to what exists)
  int target_points = 1500;  ///< instance points each CPD registers onto (farthest-point sampled)
  /// Floor of canonical points per part: a part that farthest-point sampling of the whole gave fewer gets
  /// this many of its own surface samples instead (farthest-point sampled within the part; all of them
  /// when it has fewer), so a small part's space is learned and fitted from enough points. The real mug's
  /// handle gets 150 instead of 61 of 1000 (docs/training.md). 0 turns the floor off.
  int min_part_points = 150;
  /// Part spaces agree at their seams: within this band of another part (normalised length) a part's CPD
  /// field is refitted to pass into the holistic CPD's field, which is one field across every seam, so the
  /// spaces can represent attached parts (docs/training.md). 0 keeps the part CPDs' fields as they are
  /// (the paper's training). Outside [0, 1]: UsageError.
  double seam_band = 0.08;
  /// The coupled variant's seam weights training chooses among for a category with parts: each is tried on
  /// the views of held-out training instances and the best is kept in the model, which registration uses
  /// unless asked for another (docs/training.md). One weight: that one, without trying. Each in [0, 1e6].
  std::vector<double> seam_weight_candidates = {1.0, 3.0, 10.0, 30.0};
  int latent_dimensions = 5;  ///< q per space (clamped to K - 1 for K training instances)
  double beta = 0.3;          ///< CPD kernel width (normalised length); see docs/training.md for the choice
  double lambda = 3.0;        ///< CPD smoothness weight (unitless)
  /// Kernel width (normalised length) of the CPD whose fit carries part labels to the instances: a wider
  /// field than the space's keeps the part boundaries in place (docs/training.md, "Label agreement"). 0 or
  /// `beta`: the holistic CPD's own fit, with no CPD of its own.
  double label_beta = 0.7;
  double outlier_weight = 0.05;          ///< CPD w: clean sampled surfaces have few outliers
  int max_iterations = 150;              ///< CPD iteration cap per registration
  std::optional<std::string> canonical;  ///< instance name to use as canonical; automatic when absent
  std::uint64_t seed = 1;                ///< PCA-EM seed
  /// The category's up axis in its data frame (any length > 0; kept in the model, normalised): y for
  /// ShapeNet and the kettles, z for the drills (../shared/data/README.md).
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  /// The category's real size: its instances' mean bounding-box diagonal in metres, kept in the model so
  /// that registration takes observations in metres whatever units the training files used (0: none; the
  /// observations are then in the files' units). 0.12 for mugs.
  double size = 0.0;
};

/// What training did, for logs and the closing report.
struct TrainingReport {
  struct Registration {
    std::string instance;
    std::string space;  ///< "holistic" or a part name
    int iterations = 0;
    double seconds = 0.0;
    double mean_fit = 0.0;  ///< mean distance from the registered canonical to the instance (normalised)
  };
  std::vector<Registration> registrations;
  /// Label propagation onto an instance with its own parts, against them; shares of its points per part name
  /// (the part each point was sampled from) and "all".
  struct LabelAgreement {
    /// Propagated label is a part whose surface passes through the point (within 0.1% of the instance's
    /// diagonal): its own part's, or another part's lying on it, as the kettles' lids lie on their bodies'
    /// tops, where a point's position cannot tell which file it was drawn from. The figure training reports.
    std::map<std::string, double> by_surface;
    /// Propagated label equals the part the point was sampled from.
    std::map<std::string, double> by_sampled_part;
    double shared_surface = 0.0;  ///< share of the points on more than one part's surface
  };
  std::map<std::string, LabelAgreement> label_agreement;  ///< per instance name
  std::string canonical_choice;  ///< how the canonical was chosen, with the figures behind the choice
  double seconds = 0.0;
};

/// Called with one line of progress (for example after each CPD).
using ProgressCallback = std::function<void(const std::string&)>;

/// Training's progress (core/progress.hpp) has a known end: K (1 + P) equal steps for K instances and P
/// parts, one CPD per instance other than the canonical and per space, and one PCA-EM per space; with parts,
/// one more per held-out instance of the seam weight's choice and per label CPD (an instance without its own
/// labels, or any with a `report` to fill; docs/training.md). Each
/// report's line is what that step did (as ProgressCallback gets it); the last report has done == total.
using TrainingProgress = Progress;

/// Called after each training step with how far training is.
using TrainingProgressCallback = ProgressListener;

/// The instance every other one is closest to on average (symmetric Chamfer distance of FPS samples):
/// a cheap stand-in for "reached with least deformation" (see docs/training.md). Returns its index.
std::size_t choose_canonical(const std::vector<TrainingInstance>& instances,
                             std::string* explanation = nullptr);

/// Part labels for `points` taken from the nearest point of `labelled` (labels `labelled_part`).
Eigen::VectorXi propagate_labels(const Points& labelled, const Eigen::VectorXi& labelled_part,
                                 const Points& points);

/// Trains a category. `part_names` is empty for a category without parts. With parts, the canonical
/// instance must carry its part labels; any other instance without its own labels gets them by
/// propagation through the holistic registration. Throws InputError for fewer than two instances,
/// mismatched part labels or non-finite data.
CategoryModel train_category(const std::string& category, const std::vector<TrainingInstance>& instances,
                             const std::vector<std::string>& part_names, const TrainingSettings& settings,
                             TrainingReport* report = nullptr, const ProgressCallback& progress = {});

/// train_category() reporting the fraction done as well as each line (for progress bars).
CategoryModel train_category(const std::string& category, const std::vector<TrainingInstance>& instances,
                             const std::vector<std::string>& part_names, const TrainingSettings& settings,
                             TrainingReport* report, const TrainingProgressCallback& progress);

}  // namespace partreg::core
