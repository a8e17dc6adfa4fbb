#pragma once
/// \file
/// What a registration found, as files: the result JSON that `partreg register --json` prints and the
/// app's Save result writes, and a result folder with everything a robot needs from it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::io {

/// A 4x4 matrix as four rows.
nlohmann::json matrix_json(const Eigen::Matrix4d& matrix);

/// The version of the result JSON's layout (its `format_version` key); raised when a key changes meaning.
constexpr int kResultFormatVersion = 2;

/// Where a result came from, as written into its JSON.
struct ResultSource {
  std::string model_path, observed_path;
};

/// The result as JSON: format version, model, observation, variant and every registration setting by its
/// option name (registration_options.hpp); per space its latent, pose (T_observed_canonical), scale, cost,
/// steps, stop reason and seconds; the closest-point fit (data units and normalised by the model's diagonal);
/// what the refinement did (`refinement`: enabled, and when it was, applied, points, observed, centres,
/// iterations, seconds and the mean and largest movement of the fitted points as a share of the diagonal);
/// how the pose was found (`start`: outcome searched | warm | warm_lost, and the warm start's score); where the
/// time went (`stage_seconds`: prepare, search, fits, refinement, statistics, other and total, wall seconds
/// summing to total); the total time; and `assessment` (verdict_json).
nlohmann::json result_json(const core::RegistrationResult& result, const core::RegistrationSettings& settings,
                           const ResultSource& source);

/// Adds a front end's own stage (`read`, `figures`, `transfer`) to a result JSON's `stage_seconds` and sets its
/// total to `total` (wall seconds of the whole request), so that `other` holds what no stage accounts for.
void add_stage_seconds(nlohmann::json& report, const std::string& stage, double seconds, double total);

/// The result's verdict (`verdict`: good, doubtful or failed), its `reasons` and the truth-free `figures`
/// it was judged by (verdict.hpp; lengths as fractions of the model's diagonal; an infinite pose ambiguity,
/// no distinct runner-up, and a free-space share without a depth image are null).
nlohmann::json verdict_json(const core::RegistrationResult& result);

/// The errors against a ground-truth instance (truth_errors.hpp), keys named as its fields.
nlohmann::json truth_errors_json(const core::TruthErrors& errors);

/// Writes a result folder, all of it or nothing (the folder must not exist or be empty): result.json
/// (`report`), points.ply (the deformed canonical points with their part), mesh.ply (the deformed canonical
/// mesh with its parts, when the model has one) and, when `frames` are given, frames.json (them, carried into
/// the observed frame). Returns the files written.
std::vector<std::filesystem::path> write_result_folder(const std::filesystem::path& folder,
                                                       const core::CategoryModel& model,
                                                       const core::RegistrationResult& result,
                                                       const nlohmann::json& report,
                                                       const std::vector<core::Frame>& frames = {});

}  // namespace partreg::io
