#include "partreg/io/result_file.hpp"

#include <cmath>
#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::io {

nlohmann::json matrix_json(const Eigen::Matrix4d& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({matrix(r, 0), matrix(r, 1), matrix(r, 2), matrix(r, 3)});
  return rows;
}

namespace {

// What the refinement did: whether it was asked for, whether it ran (enough observed points), what it counted
// and how far it moved the space fit.
nlohmann::json refinement_json(const core::RefinementField& field, const core::RefinementSettings& settings) {
  if (!settings.enabled) return {{"enabled", false}};
  return {{"enabled", true},
          {"applied", !field.empty()},
          {"points", field.points},
          {"observed", field.observed},
          {"matched", field.matched},
          {"outlier_weight", field.outlier_weight},
          {"noise_normalised", field.noise},
          {"kernel_width_normalised", field.width},
          {"centres", field.centres.rows()},
          {"iterations", field.iterations},
          {"seconds", field.seconds},
          {"mean_movement_normalised", field.mean_movement},
          {"max_movement_normalised", field.max_movement}};
}

// Whether the space fits ended in a Gaussian mixture, on the noise read off the holistic fit.
nlohmann::json mixture_json(const core::MixtureFinish& mixture) {
  return {{"applied", mixture.applied},
          {"noise_normalised", mixture.noise},
          {"sigma_normalised", mixture.sigma}};
}

// Where the time went (core::StageSeconds): the stages of register_observation, summing to `total`; a front end
// adds its own (reading, transferring) with add_stage_seconds.
nlohmann::json stage_seconds_json(const core::StageSeconds& stages, double total) {
  return {{"prepare", stages.prepare}, {"search", stages.search},         {"fits", stages.fits},
          {"refinement", stages.refinement}, {"statistics", stages.statistics}, {"other", total - stages.sum()},
          {"total", total}};
}

// A number that may be infinite or unset: JSON has no infinity, so null.
nlohmann::json finite_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

}  // namespace

void add_stage_seconds(nlohmann::json& report, const std::string& stage, double seconds, double total) {
  nlohmann::json& stages = report.at("stage_seconds");
  stages[stage] = seconds;
  double sum = 0.0;
  for (const auto& [name, value] : stages.items())
    if (name != "other" && name != "total") sum += value.get<double>();
  stages["other"] = total - sum;
  stages["total"] = total;
}

nlohmann::json verdict_json(const core::RegistrationResult& result) {
  const core::TrustFigures& f = result.figures;
  nlohmann::json json = nlohmann::json::object();
  json["verdict"] = core::enum_name(result.assessment.verdict);
  json["reasons"] = nlohmann::json::array();
  for (const std::string& reason : result.assessment.reasons) json["reasons"].push_back(reason);
  nlohmann::json& figures = json["figures"];
  figures["observed_rms_normalised"] = f.observed_rms;
  figures["inlier_share"] = f.inlier_share;
  figures["latent_distance"] = f.latent_distance;
  figures["refinement_movement_normalised"] = f.refinement_movement;
  figures["pose_ambiguity"] = finite_or_null(f.pose_ambiguity);
  figures["seam_gap_mean_normalised"] = f.seam_gap_mean;
  figures["seam_gap_max_normalised"] = f.seam_gap_max;
  figures["mesh_stretch"] = f.mesh_stretch;
  figures["scale"] = f.scale;
  figures["scale_at_bound"] = f.scale_at_bound;
  figures["free_space_violation"] =
      f.free_space_violation ? nlohmann::json(*f.free_space_violation) : nlohmann::json();
  return json;
}

nlohmann::json result_json(const core::RegistrationResult& result, const core::RegistrationSettings& settings,
                           const ResultSource& source) {
  nlohmann::json spaces = nlohmann::json::array();
  for (const core::SpaceFit& fit : result.fits)
    spaces.push_back(
        {{"space", fit.space},
         {"latent", std::vector<double>(fit.latent.data(), fit.latent.data() + fit.latent.size())},
         {"T_observed_canonical", matrix_json(fit.T_observed_canonical)},
         {"scale", fit.scale},
         {"cost", fit.cost},
         {"iterations", fit.iterations},
         {"stop_reason", core::enum_name(fit.stop_reason)},
         {"pose_hypotheses", fit.hypotheses},
         {"selection_score", fit.score},
         {"runner_up_score", finite_or_null(fit.runner_up_score)},
         {"runner_up_shift_normalised", fit.runner_up_shift},
         {"latent_distance", fit.latent_distance},
         {"seconds", fit.seconds}});
  nlohmann::json request = nlohmann::json::object();
  for (const auto& [name, value] : core::registration_option_values(settings)) request[name] = value;
  return {{"format_version", kResultFormatVersion},
          {"model", source.model_path},
          {"observed", source.observed_path},
          {"variant", core::enum_name(result.variant)},
          {"settings", request},
          {"spaces", spaces},
          {"fit",
           {{"mean", result.fit.mean},
            {"p90", result.fit.p90},
            {"mean_normalised", result.fit.mean_normalised},
            {"p90_normalised", result.fit.p90_normalised},
            {"strays", result.fit.strays}}},
          {"mixture", mixture_json(result.mixture)},
          {"refinement", refinement_json(result.refinement, settings.refinement)},
          {"start",
           {{"outcome", core::enum_name(result.start)},
            {"warm_score", result.warm_score},
            {"pose_score", result.pose_score}}},
          {"stage_seconds", stage_seconds_json(result.stages, result.seconds)},
          {"assessment", verdict_json(result)},
          {"seconds", result.seconds}};
}

nlohmann::json truth_errors_json(const core::TruthErrors& errors) {
  nlohmann::json json = {{"diagonal", errors.diagonal},
                         {"eq5", errors.eq5},
                         {"eq5_per_diagonal2", errors.eq5_per_diagonal2},
                         {"reverse_eq5", errors.reverse_eq5},
                         {"symmetric_rms_per_diagonal", errors.symmetric_rms_per_diagonal},
                         {"chamfer", errors.chamfer},
                         {"chamfer_per_diagonal", errors.chamfer_per_diagonal},
                         {"part_eq5_per_diagonal2", errors.part_eq5_per_diagonal2}};
  if (errors.correspondence_per_diagonal)
    json["correspondence_per_diagonal"] = *errors.correspondence_per_diagonal;
  if (errors.own_part_rms_mean_per_diagonal) {
    json["own_part_rms_per_diagonal"] = errors.own_part_rms_per_diagonal;
    json["own_part_rms_mean_per_diagonal"] = *errors.own_part_rms_mean_per_diagonal;
  }
  return json;
}

std::vector<std::filesystem::path> write_result_folder(const std::filesystem::path& folder,
                                                       const core::CategoryModel& model,
                                                       const core::RegistrationResult& result,
                                                       const nlohmann::json& report,
                                                       const std::vector<core::Frame>& frames) {
  StagedFolder staged(folder);
  const std::filesystem::path& out = staged.staging();
  std::vector<std::string> names = {"result.json", "points.ply"};
  {
    std::ofstream json(out / "result.json");
    json << report.dump(2) << '\n';
    if (!json) throw InputError("cannot write " + (folder / "result.json").string());
  }
  PointAttributes attributes;
  attributes.integers["part"] = result.part;
  write_cloud_ply(out / "points.ply", core::Cloud{result.deformed, {}}, attributes);
  if (model.canonical_mesh.faces.rows() > 0) {
    write_mesh(out / "mesh.ply", core::deform_mesh(model, result), &model.mesh_vertex_part);
    names.push_back("mesh.ply");
  }
  if (!frames.empty()) {
    write_frames_file(out / "frames.json", core::transfer_frames(model, result, frames));
    names.push_back("frames.json");
  }
  staged.commit();
  std::vector<std::filesystem::path> written;
  for (const std::string& name : names) written.push_back(folder / name);
  return written;
}

}  // namespace partreg::io
