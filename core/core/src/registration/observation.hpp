#pragma once
// The observed cloud as registration sees it (internal to partreg_core): thinned once in data units, centred
// and scaled into the model's normalised frame, its points that stand alone flagged as possible strays, and
// split by part for the part fits.

#include <optional>
#include <vector>

#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/core/space/category_model.hpp"
#include "space_solver.hpp"

namespace partreg::core::detail {

/// The observation the fits match, in the model's normalised frame: `centroid` gets the observed cloud's
/// centroid (data units), which the normalised frame is centred on; `statistics_points` the points the fit
/// statistics read when the cloud was thinned (none when every point is read). Refuses a cloud of fewer than
/// 10 points, one with NaN or infinite points, or one far off the model's size.
Observation prepare_observation(const CategoryModel& model, const Points& observed,
                                const RegistrationSettings& settings, Eigen::Vector3d& centroid,
                                std::optional<Points>& statistics_points);

/// Splits the observation by part: each observed point goes to the part of the nearest point of the
/// holistic fit (indexed by space; a part with fewer than 10 points gets no observation of its own).
std::vector<Observation> split_observation(const CategoryModel& model, const Observation& observation,
                                           const Points& holistic_posed);

/// The observation the refinement follows: the space fit's strays left out, as the fit left them out.
Points without_strays(const Observation& observation, const Points& fitted);

/// Observed points the final fit left out (FitStatistics::strays).
int count_strays(const Observation& observation, const Points& fitted);

}  // namespace partreg::core::detail
