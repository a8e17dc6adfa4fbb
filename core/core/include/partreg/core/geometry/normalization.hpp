#pragma once
/// \file
/// Centre-and-scale normalisation. Every CPD length parameter in partreg (beta, sigma, noise levels)
/// is stated in normalised units: the reference set is centred on its bounding-box centre and scaled
/// so that its bounding-box diagonal is 1.

#include "partreg/core/types.hpp"

namespace partreg::core {

/// Maps data coordinates to normalised ones: normalised = (data - centre) / scale.
struct Normalization {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< bounding-box centre, data units
  double scale = 1.0;                                ///< bounding-box diagonal, data units (> 0)

  /// The normalisation that takes `reference` to a unit-diagonal box centred at the origin.
  /// Throws InputError for an empty set, non-finite points or a zero-size box.
  static Normalization fit(const Points& reference);

  Points apply(const Points& data_points) const;       ///< data -> normalised
  Points undo(const Points& normalised_points) const;  ///< normalised -> data
  double to_normalised(double data_length) const { return data_length / scale; }
  double to_data(double normalised_length) const { return normalised_length * scale; }
};

/// Length of the bounding-box diagonal of a non-empty set, in its own units.
double bounding_box_diagonal(const Points& points);

}  // namespace partreg::core
