#pragma once
/// \file
/// A trained category: its canonical instance (points and mesh, with parts), the normalisation that maps the
/// category's data frame to normalised units, and one shape space for the whole object plus one per part.
/// This is what `partreg train` writes and every later command loads.

#include <optional>
#include <string>
#include <vector>

#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/space/shape_space.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

/// One seam weight tried when training chose the coupled variant's (TrainingRecord::seam_weight_trials).
struct SeamWeightTrial {
  double weight = 0.0;
  double error = 0.0;  ///< mean symmetric RMS over the held-out instances' views, fraction of the diagonal
};

/// How a category model was trained (kept in the model file so results can be reproduced).
struct TrainingRecord {
  std::vector<std::string> instances;  ///< training instance names, in training order
  std::string canonical;               ///< name of the instance chosen as canonical
  std::string canonical_choice;        ///< "given" or how it was chosen automatically
  int canonical_points = 0;            ///< M (with every part's floor applied)
  int min_part_points = 0;             ///< floor of canonical points per part used (0: none, older files)
  double seam_band = 0.0;              ///< band the part fields were refitted in at seams (0: none, older files)
  /// The coupled variant's seam weight for this category, which registration uses unless asked for another
  /// (unset in models without parts and older files: registration then uses kDefaultSeamWeight).
  std::optional<double> seam_weight;
  std::string seam_weight_choice;      ///< "given" or the figures it was chosen by (empty when none was)
  /// The candidates' errors it was chosen by (empty when it was given).
  std::vector<SeamWeightTrial> seam_weight_trials;
  double beta = 0.0;                   ///< CPD kernel width (normalised units)
  double lambda = 0.0;                 ///< CPD smoothness weight (unitless)
  double outlier_weight = 0.0;         ///< CPD w
  int latent_dimensions = 0;           ///< requested q (a space may hold fewer: q <= K - 1)
  std::uint64_t seed = 0;              ///< sampling seed
};

/// A trained category model. All geometry is in normalised units: data = normalization.undo(normalised).
struct CategoryModel {
  std::string category;            ///< e.g. "kettles"
  Normalization normalization;     ///< category data frame <-> normalised units
  Points canonical;                ///< M canonical points (normalised units)
  Eigen::VectorXi canonical_part;  ///< part index per canonical point (all 0 for a category without parts)
  std::vector<std::string> part_names;  ///< index -> name; empty for a category without parts
  Mesh canonical_mesh;                  ///< canonical surface (normalised units); may be empty for cloud data
  Eigen::VectorXi mesh_vertex_part;     ///< part index per mesh vertex (empty with an empty mesh)
  std::vector<ShapeSpace> spaces;       ///< spaces[0] is holistic; then one per part, in part_names order
  TrainingRecord training;
  /// The holistic CPD weight field W_i of each training instance (K x 3M; row i is W_i vectorised as in
  /// shape_space.hpp, in training.instances order; the canonical's own row is zero). Its fitted shape is
  /// canonical + G(C, C) W_i, and any surface point z moves by G(z, C) W_i.
  Eigen::MatrixXd training_weights;
  /// The category's up axis in its data frame (unit length; the normalised frame has the same axes): the
  /// pose search turns about it unless a registration names another. +y for files from before it was kept.
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  /// The category's real size (`partreg train --size`): its training instances' mean bounding-box diagonal,
  /// in metres. With it, observations are in metres whatever units the training files used; unset, they
  /// are in the model's data units.
  std::optional<double> size;
  /// The training instances' mean bounding-box diagonal in data units (0 in files from before it was kept).
  double data_size = 0.0;

  /// Observation units per data unit: size / data_size for a model with a size, else 1.
  double observed_per_data() const { return size && data_size > 0.0 ? *size / data_size : 1.0; }
  /// The canonical's bounding-box diagonal in observation units: what every registration figure is a
  /// fraction of.
  double observed_diagonal() const { return normalization.scale * observed_per_data(); }

  bool has_parts() const { return !part_names.empty(); }
  const ShapeSpace& holistic() const { return spaces.front(); }
  /// The space of a part by name (or "holistic"); throws UsageError listing the names when there is none.
  const ShapeSpace& space(const std::string& name) const;
  /// W_i of training instance `instance` (index into training.instances) as an M x 3 matrix.
  Points training_weight_field(int instance) const;
  /// The canonical rows belonging to part `part_index`.
  std::vector<int> part_rows(int part_index) const;
  /// Checks internal consistency (sizes, indices, finiteness); throws InputError naming what is wrong.
  void validate() const;
};

}  // namespace partreg::core
