// The verdict's Python face: what a registration says of itself without the truth
// (core/registration/verdict.hpp), added to the classes types.cpp made (Model, SpaceFit, RegistrationResult).
#include <pybind11/stl.h>

#include <limits>

#include "bindings.hpp"
#include "partreg/core/registration/registration.hpp"

namespace partreg::python {

namespace py = pybind11;

void bind_verdict(py::module_& m) {
  py::class_<core::TrustFigures>(m, "TrustFigures",
                                 "What a registration says of itself without the truth; lengths are shares of "
                                 "the model's diagonal.")
      .def_readonly("observed_rms", &core::TrustFigures::observed_rms,
                    "RMS distance from the observed points to the deformed model's surface")
      .def_readonly("inlier_share", &core::TrustFigures::inlier_share,
                    "observed points within the verdict's inlier distance of that surface, [0, 1]")
      .def_readonly("latent_distance", &core::TrustFigures::latent_distance,
                    "largest Mahalanobis distance of a fitted latent (training standard deviations)")
      .def_readonly("refinement_movement", &core::TrustFigures::refinement_movement,
                    "mean movement of the fit beyond the shape space")
      .def_readonly("pose_ambiguity", &core::TrustFigures::pose_ambiguity,
                    "distinct runner-up's score / the winner's (inf: none)")
      .def_readonly("seam_gap_mean", &core::TrustFigures::seam_gap_mean)
      .def_readonly("seam_gap_max", &core::TrustFigures::seam_gap_max)
      .def_readonly("mesh_stretch", &core::TrustFigures::mesh_stretch, "largest deformed / canonical edge (0: no mesh)")
      .def_readonly("scale", &core::TrustFigures::scale, "the whole object's fitted scale")
      .def_readonly("scale_at_bound", &core::TrustFigures::scale_at_bound, "the fitted scale ended at scale_limit's bound")
      .def_readonly("free_space_violation", &core::TrustFigures::free_space_violation,
                    "share of model points in front of measured depth (None without a depth image)");
  using Result = py::class_<core::RegistrationResult, std::shared_ptr<core::RegistrationResult>>;
  auto result = py::reinterpret_borrow<Result>(m.attr("RegistrationResult"));
  result.def_readonly("figures", &core::RegistrationResult::figures)
      .def_property_readonly(
          "verdict", [](const core::RegistrationResult& s) { return core::enum_name(s.assessment.verdict); },
          "'good', 'doubtful' or 'failed'")
      .def_property_readonly(
          "reasons", [](const core::RegistrationResult& s) { return s.assessment.reasons; },
          "one line per figure past a threshold; empty when good");
  auto fit = py::reinterpret_borrow<py::class_<core::SpaceFit>>(m.attr("SpaceFit"));
  fit.def_readonly("latent_distance", &core::SpaceFit::latent_distance, "Mahalanobis distance (training sd)")
      .def_readonly("runner_up_shift", &core::SpaceFit::runner_up_shift,
                    "RMS distance between the runner-up's posed shape and the winner's, / the diagonal");
  using Model = py::class_<core::CategoryModel, std::shared_ptr<core::CategoryModel>>;
  auto model = py::reinterpret_borrow<Model>(m.attr("Model"));
  model.def_property_readonly(
      "size", [](const core::CategoryModel& s) { return s.size; },
      "the category's real size in metres (train size=...): observations in metres; None: in the data's units");
}

}  // namespace partreg::python
