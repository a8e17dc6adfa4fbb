// The module's classes. Large arrays are read-only views of the C++ object that owns them (arrays.hpp).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/eval/views.hpp"

namespace partreg::python {
namespace {

// A property returning a view of the member `field` of `Class`, kept alive by the Python object.
template <typename Class, typename Getter>
void view_property(py::class_<Class, std::shared_ptr<Class>>& cls, const char* name, Getter getter,
                   const char* doc) {
  cls.def_property_readonly(
      name, [getter](py::object self) { return getter(self.cast<Class&>(), self); }, doc);
}

// A latent of `space` (q values); UsageError otherwise (the library does not check sizes).
Eigen::VectorXd latent_of(const core::ShapeSpace& space, py::handle latent) {
  Eigen::VectorXd values = to_vector(latent, "latent");
  if (values.size() != space.dimensions())
    throw UsageError("latent has " + std::to_string(values.size()) + " values; space " + space.name + " has " +
                     std::to_string(space.dimensions()) + " dimensions");
  return values;
}

void bind_mesh(py::module_& m) {
  py::class_<core::Mesh, std::shared_ptr<core::Mesh>> mesh(m, "Mesh", "A triangle mesh.");
  mesh.def(py::init([](py::handle vertices, py::handle faces) {
             core::Mesh made;
             made.vertices = to_points(vertices, "vertices");
             made.faces = to_faces(faces, "faces");
             return made;
           }),
           py::arg("vertices"), py::arg("faces"),
           "A mesh from vertices (float64 (V, 3)) and faces (integer (F, 3) vertex indices).");
  view_property(mesh, "vertices", [](core::Mesh& s, py::handle o) { return points_view(s.vertices, o, Access::writeable); },
                "(V, 3) float64 vertex positions (frame and units as produced: data units)");
  view_property(mesh, "faces", [](core::Mesh& s, py::handle o) { return faces_view(s.faces, o, Access::writeable); },
                "(F, 3) int32 vertex indices, counter-clockwise seen from outside where known");
  view_property(mesh, "normals", [](core::Mesh& s, py::handle o) { return points_view(s.normals, o, Access::writeable); },
                "(V, 3) unit vertex normals, or (0, 3)");
  mesh.def("__repr__", [](const core::Mesh& s) {
    return "<partreg.Mesh " + std::to_string(s.vertices.rows()) + " vertices, " +
           std::to_string(s.faces.rows()) + " faces>";
  });
}

void bind_frame(py::module_& m) {
  py::class_<core::Frame, std::shared_ptr<core::Frame>>(m, "Frame",
                                                        "A frame attached to an object (a grasp pose).")
      .def(py::init([](const std::string& name, py::handle position, py::handle rotation) {
             core::Frame frame;
             frame.name = name;
             frame.position = to_matrix(position, 3, 1, "position").col(0);
             if (!rotation.is_none()) frame.rotation = to_matrix(rotation, 3, 3, "rotation");
             return frame;
           }),
           py::arg("name"), py::arg("position"), py::arg("rotation") = py::none(),
           "position: (3,) in the category's data frame (data units); rotation: (3, 3), columns are the "
           "frame's axes (identity when omitted).")
      .def_readonly("name", &core::Frame::name)
      .def_property_readonly(
          "position", [](const core::Frame& f) { return copy_vector(f.position); },
          "(3,) position (data units)")
      .def_property_readonly(
          "rotation", [](const core::Frame& f) { return copy_matrix(f.rotation); },
          "(3, 3) rotation, columns are the frame's axes");
}

void bind_shape_space(py::module_& m) {
  py::class_<core::ShapeSpace, std::shared_ptr<core::ShapeSpace>> space(
      m, "ShapeSpace",
      "One learned shape space (the whole object or a part). Lengths in the category's normalised units "
      "(canonical diagonal 1); the canonical frame.");
  space.def_readonly("name", &core::ShapeSpace::name, "'holistic' or the part's name")
      .def_readonly("point_indices", &core::ShapeSpace::point_indices,
                    "rows of the holistic canonical this space deforms")
      .def_readonly("beta", &core::ShapeSpace::beta, "CPD kernel width used in training (normalised length)")
      .def_readonly("total_variance", &core::ShapeSpace::total_variance,
                    "total variance of the training displacements (normalised length squared)")
      .def_property_readonly("dimensions", &core::ShapeSpace::dimensions, "q, the latent dimension")
      .def_property_readonly("point_count", &core::ShapeSpace::point_count, "M, canonical points")
      .def("explained_fraction",
           [](const core::ShapeSpace& s) { return copy_vector(s.explained_fraction()); },
           "(q,) share of the training variance each dimension explains")
      .def("weights", [](const core::ShapeSpace& s, py::handle latent) {
             return owned_points(s.weights(latent_of(s, latent)));
           }, py::arg("latent"), "W(x) = mean + basis x: (M, 3) kernel weights at a latent (q,)")
      .def("deformed", [](const core::ShapeSpace& s, py::handle latent) {
             return owned_points(s.deformed(latent_of(s, latent)));
           }, py::arg("latent"),
           "The shape at a latent (q,): C + G W(x), (M, 3), normalised units, canonical frame");
  view_property(space, "canonical", [](core::ShapeSpace& s, py::handle o) { return points_view(s.canonical, o); },
                "(M, 3) canonical points C (normalised units)");
  view_property(space, "mean", [](core::ShapeSpace& s, py::handle o) { return vector_view(s.mean, o); },
                "(3M,) mean of the vectorised training weight fields (row by row: w1x, w1y, w1z, w2x, ...)");
  view_property(space, "basis", [](core::ShapeSpace& s, py::handle o) { return matrix_view(s.basis, o); },
                "(3M, q) weight fields of the principal directions");
  view_property(space, "variances", [](core::ShapeSpace& s, py::handle o) { return vector_view(s.variances, o); },
                "(q,) variance of the training latents per direction, descending");
  view_property(space, "kernel_mean", [](core::ShapeSpace& s, py::handle o) { return vector_view(s.kernel_mean, o); },
                "(3M,) the canonical's mean displacement vec(G W_mean) (normalised units)");
  view_property(space, "kernel_basis", [](core::ShapeSpace& s, py::handle o) { return matrix_view(s.kernel_basis, o); },
                "(3M, q) displacement per unit latent, orthonormal columns");
  view_property(space, "training_latents",
                [](core::ShapeSpace& s, py::handle o) { return matrix_view(s.training_latents, o); },
                "(K, q) latent of each training instance, training order");
  space.def("__repr__", [](const core::ShapeSpace& s) {
    return "<partreg.ShapeSpace " + s.name + ": " + std::to_string(s.point_count()) + " points, " +
           std::to_string(s.dimensions()) + " dimensions>";
  });
}

void bind_model(py::module_& m) {
  py::class_<core::CategoryModel, std::shared_ptr<core::CategoryModel>> model(
      m, "Model",
      "A trained category (what `partreg train` writes). Geometry is stored in normalised units: data = "
      "centre + scale * normalised.");
  model.def_readonly("category", &core::CategoryModel::category)
      .def_readonly("part_names", &core::CategoryModel::part_names, "part index -> name; empty without parts")
      .def_property_readonly("has_parts", &core::CategoryModel::has_parts)
      .def_property_readonly(
          "scale", [](const core::CategoryModel& s) { return s.normalization.scale; },
          "the canonical's bounding-box diagonal (data units)")
      .def_property_readonly(
          "centre", [](const core::CategoryModel& s) { return copy_vector(s.normalization.centre); },
          "(3,) the canonical's bounding-box centre (data units)")
      .def_property_readonly("training_instances",
                             [](const core::CategoryModel& s) { return s.training.instances; })
      .def_property_readonly("canonical_name",
                             [](const core::CategoryModel& s) { return s.training.canonical; })
      .def_property_readonly(
          "seam_weight", [](const core::CategoryModel& s) { return s.training.seam_weight; },
          "the coupled variant's seam weight training chose for the category (None without "
          "parts; register's seam_weight='model' uses it)")
      .def_property_readonly(
          "seam_weight_choice", [](const core::CategoryModel& s) { return s.training.seam_weight_choice; },
          "how seam_weight was chosen: 'given', or the candidates' errors")
      .def_property_readonly(
          "seam_weight_trials",
          [](const core::CategoryModel& s) {
            std::map<double, double> errors;
            for (const core::SeamWeightTrial& trial : s.training.seam_weight_trials)
              errors[trial.weight] = trial.error;
            return errors;
          },
          "each candidate seam weight's mean symmetric RMS error (fraction of the diagonal) on the held-out "
          "instances' views it was chosen by ({} when it was given)")
      .def_property_readonly(
          "spaces",
          [](py::object self) {
            py::list spaces;
            for (const core::ShapeSpace& space : self.cast<core::CategoryModel&>().spaces)
              spaces.append(py::cast(&space, py::return_value_policy::reference_internal, self));
            return spaces;
          },
          "the shape spaces: holistic first, then one per part in part_names order")
      .def("space", &core::CategoryModel::space, py::arg("name"), py::return_value_policy::reference_internal,
           "The space of a part by name, or 'holistic'; UsageError listing the names otherwise.")
      .def(
          "to_data",
          [](const core::CategoryModel& s, py::handle points) {
            return owned_points(s.normalization.undo(to_points(points, "points")));
          },
          py::arg("points"), "Normalised units -> the category's data frame and units")
      .def(
          "shape_at",
          [](const core::CategoryModel& s, py::handle latent, const std::string& name) {
            const core::ShapeSpace& space = s.space(name);
            return owned_points(s.normalization.undo(space.deformed(latent_of(space, latent))));
          },
          py::arg("latent"), py::arg("space") = "holistic",
          "The canonical of `space` deformed to a latent (q,), in the category's data frame (data units)")
      .def_property_readonly(
          "canonical_mesh",
          [](const core::CategoryModel& s) {
            return std::make_shared<core::Mesh>(s.canonical_mesh);  // a copy: the model stays as trained
          },
          "a copy of the canonical surface (normalised units); empty for a model trained on clouds");
  view_property(model, "canonical", [](core::CategoryModel& s, py::handle o) { return points_view(s.canonical, o); },
                "(M, 3) canonical points (normalised units)");
  view_property(model, "canonical_part",
                [](core::CategoryModel& s, py::handle o) { return indices_view(s.canonical_part, o); },
                "(M,) part index per canonical point");
  view_property(model, "mesh_vertex_part",
                [](core::CategoryModel& s, py::handle o) { return indices_view(s.mesh_vertex_part, o); },
                "(V,) part index per canonical mesh vertex (empty without a mesh)");
  model.def("__repr__", [](const core::CategoryModel& s) {
    return "<partreg.Model " + s.category + ": " + std::to_string(s.canonical.rows()) + " canonical points, " +
           std::to_string(s.spaces.size()) + " spaces>";
  });
}

void bind_registration_result(py::module_& m) {
  py::class_<core::FitStatistics>(m, "FitStatistics",
                                  "Closest-point distances from the deformed canonical to the observation.")
      .def_readonly("mean", &core::FitStatistics::mean, "data units")
      .def_readonly("p90", &core::FitStatistics::p90, "90th percentile, data units")
      .def_readonly("mean_normalised", &core::FitStatistics::mean_normalised, "mean / the model's diagonal")
      .def_readonly("p90_normalised", &core::FitStatistics::p90_normalised, "p90 / the model's diagonal")
      .def_readonly("strays", &core::FitStatistics::strays,
                    "observed points left out as strays before the fit (setting stray_limit)");
  py::class_<core::SpaceFit>(m, "SpaceFit", "The fit of one shape space.")
      .def_readonly("space", &core::SpaceFit::space)
      .def_property_readonly("latent", [](const core::SpaceFit& s) { return copy_vector(s.latent); }, "(q,)")
      .def_property_readonly("T_observed_canonical",
                             [](const core::SpaceFit& s) { return copy_matrix(s.T_observed_canonical); },
                             "(4, 4): canonical data frame -> observed frame")
      .def_readonly("scale", &core::SpaceFit::scale)
      .def_readonly("cost", &core::SpaceFit::cost)
      .def_readonly("iterations", &core::SpaceFit::iterations)
      .def_property_readonly("stop_reason", [](const core::SpaceFit& s) { return core::enum_name(s.stop_reason); },
                             "'converged', 'max_iterations' or 'no_pairs'")
      .def_readonly("seconds", &core::SpaceFit::seconds)
      .def_readonly("hypotheses", &core::SpaceFit::hypotheses, "starting poses the search tried")
      .def_readonly("score", &core::SpaceFit::score, "the winner's selection score (setting score)")
      .def_readonly("runner_up_score", &core::SpaceFit::runner_up_score,
                    "the best other finalist's score; inf when there was none (near score: ambiguous)");
  py::class_<core::HistoryStep>(m, "HistoryStep", "The state after one outer step of one space.")
      .def_readonly("space", &core::HistoryStep::space)
      .def_property_readonly("latent", [](const core::HistoryStep& s) { return copy_vector(s.latent); })
      .def_property_readonly("T_observed_canonical",
                             [](const core::HistoryStep& s) { return copy_matrix(s.T_observed_canonical); })
      .def_readonly("cost", &core::HistoryStep::cost)
      .def_readonly("seconds", &core::HistoryStep::seconds, "since the start of this space's registration");
  py::class_<core::RefinementField>(m, "Refinement", "What the fit beyond the shape space did (refine=True).")
      .def_property_readonly("applied", [](const core::RefinementField& s) { return !s.empty(); },
                             "False when it was off or saw fewer than 10 observed points (the space fit stands)")
      .def_readonly("points", &core::RefinementField::points, "fitted points refined (0 when off)")
      .def_readonly("observed", &core::RefinementField::observed, "of those, the ones counted as observed")
      .def_readonly("matched", &core::RefinementField::matched,
                    "observed points the E-step matched (the rest, far from the fit and alone, are strays)")
      .def_readonly("noise", &core::RefinementField::noise,
                    "the observation's noise (spread off the fit from point to point), / the model's diagonal")
      .def_readonly("outlier_weight", &core::RefinementField::outlier_weight,
                    "the E-step's outlier weight: refine_outliers, or the share left out as strays if larger")
      .def_readonly("width", &core::RefinementField::width,
                    "the kernel width used: refine_beta, or refine_noise_width x noise when wider, / the "
                    "model's diagonal")
      .def_readonly("iterations", &core::RefinementField::iterations, "EM iterations run")
      .def_readonly("seconds", &core::RefinementField::seconds)
      .def_readonly("mean_movement", &core::RefinementField::mean_movement,
                    "mean distance it moved the fitted points, / the model's diagonal")
      .def_readonly("max_movement", &core::RefinementField::max_movement,
                    "largest distance it moved a fitted point, / the model's diagonal");
  py::class_<core::MixtureFinish>(m, "MixtureFinish",
                                  "Whether the space fits ended in a Gaussian mixture (above mixture_noise).")
      .def_readonly("applied", &core::MixtureFinish::applied,
                    "the holistic fit, and coupled's joint problem after it, continued in the mixture")
      .def_readonly("noise", &core::MixtureFinish::noise,
                    "the noise read off the holistic space fit, / the model's diagonal (0: not read, as for partwise)")
      .def_readonly("sigma", &core::MixtureFinish::sigma,
                    "the mixture's final standard deviation per axis, / the model's diagonal (0: not applied)");
  py::class_<core::RegistrationResult, std::shared_ptr<core::RegistrationResult>> result(
      m, "RegistrationResult", "What register() found.");
  result.def_property_readonly("variant", [](const core::RegistrationResult& s) { return core::enum_name(s.variant); })
      .def_readonly("fits", &core::RegistrationResult::fits, "per space: holistic first where it ran, then parts")
      .def_readonly("history", &core::RegistrationResult::history, "every outer step of every space, in order")
      .def_readonly("fit", &core::RegistrationResult::fit)
      .def_readonly("refinement", &core::RegistrationResult::refinement, "what the refinement did")
      .def_readonly("mixture", &core::RegistrationResult::mixture,
                    "whether the space fits ended in a Gaussian mixture, and on what noise")
      .def_readonly("seconds", &core::RegistrationResult::seconds)
      .def_property_readonly("start", [](const core::RegistrationResult& s) { return core::enum_name(s.start); },
                             "how the pose was found: 'searched', 'warm' (the warm start held) or 'warm_lost'")
      .def_readonly("warm_score", &core::RegistrationResult::warm_score,
                    "the warm start's fit's symmetric selection score (normalised length; 0 without one)")
      .def_readonly("pose_score", &core::RegistrationResult::pose_score,
                    "the holistic fit's symmetric selection score (normalised length): a warm start from this "
                    "result is held to it")
      .def_property_readonly(
          "stage_seconds",
          [](const core::RegistrationResult& s) {
            const core::StageSeconds& t = s.stages;
            return std::map<std::string, double>{{"prepare", t.prepare},       {"search", t.search},
                                                 {"fits", t.fits},             {"refinement", t.refinement},
                                                 {"statistics", t.statistics}, {"other", s.seconds - t.sum()},
                                                 {"total", s.seconds}};
          },
          "wall seconds of each stage, summing to total")
      .def("space_fit", [](const core::RegistrationResult& s, const std::string& name) {
             for (const core::SpaceFit& fit : s.fits)
               if (fit.space == name) return fit;
             throw UsageError("no space '" + name + "' in this result");
           }, py::arg("name"), "The fit of one space by name; UsageError when it did not run.");
  view_property(result, "deformed",
                [](core::RegistrationResult& s, py::handle o) { return points_view(s.deformed, o, Access::writeable); },
                "(M, 3) deformed canonical points in the observed frame (data units)");
  view_property(result, "part", [](core::RegistrationResult& s, py::handle o) { return indices_view(s.part, o, Access::writeable); },
                "(M,) part index per deformed point");
}

void bind_cpd_results(py::module_& m) {
  py::class_<core::RigidCpdResult, std::shared_ptr<core::RigidCpdResult>> rigid(
      m, "RigidCpdResult", "target ~ scale * rotation * source + translation");
  rigid.def_property_readonly("rotation", [](const core::RigidCpdResult& s) { return copy_matrix(s.rotation); })
      .def_property_readonly("translation", [](const core::RigidCpdResult& s) { return copy_vector(s.translation); })
      .def_readonly("scale", &core::RigidCpdResult::scale)
      .def_property_readonly("T_target_source", [](const core::RigidCpdResult& s) { return copy_matrix(s.T_target_source()); },
                             "(4, 4) source coordinates -> target frame");
  py::class_<core::AffineCpdResult, std::shared_ptr<core::AffineCpdResult>> affine(
      m, "AffineCpdResult", "target ~ linear * source + translation");
  affine.def_property_readonly("linear", [](const core::AffineCpdResult& s) { return copy_matrix(s.linear); })
      .def_property_readonly("translation", [](const core::AffineCpdResult& s) { return copy_vector(s.translation); });
  py::class_<core::NonrigidCpdResult, std::shared_ptr<core::NonrigidCpdResult>> nonrigid(
      m, "NonrigidCpdResult", "moved = source + G(source, source) W");
  nonrigid.def_readonly("beta", &core::NonrigidCpdResult::beta, "kernel width used (working-frame units)")
      .def_readonly("kernel_rank", &core::NonrigidCpdResult::kernel_rank, "eigenpairs used (0: exact solver)")
      .def("apply", [](const core::NonrigidCpdResult& s, py::handle points) {
             const core::Points z = to_points(points, "points");
             py::gil_scoped_release release;
             core::Points moved = s.apply(z);
             py::gil_scoped_acquire acquire;
             return owned_points(std::move(moved));
           }, py::arg("points"), "Moves any points attached to the source as the source moved (caller's frame)");
  view_property(nonrigid, "weights",
                [](core::NonrigidCpdResult& s, py::handle o) { return points_view(s.weights, o, Access::writeable); },
                "(M, 3) W in the working frame (normalised when normalize was on)");
  // What every mode reports.
  auto common = [](auto& cls) {
    using Result = typename std::remove_reference_t<decltype(cls)>::type;
    cls.def_readonly("sigma2", &Result::sigma2, "final Gaussian variance (normalised units squared)")
        .def_readonly("iterations", &Result::iterations)
        .def_property_readonly(
            "stop_reason", [](const Result& s) { return std::string(core::to_string(s.stop_reason)); },
            "'converged', 'max_iterations', 'polish_limit' (the full sets' 10 iterations after coarse "
            "subsets) or 'degenerate'")
        .def_readonly("seconds", &Result::seconds);
    cls.def_property_readonly("moved", [](py::object self) { return points_view(self.cast<Result&>().moved, self, Access::writeable); },
                              "(N, 3) the source after registration, in the target's frame");
  };
  common(rigid);
  common(affine);
  common(nonrigid);
}

void bind_view(py::module_& m) {
  py::class_<eval::View, std::shared_ptr<eval::View>> view(m, "View", "One partial view, in the object's frame and units.");
  view.def_property_readonly("viewpoint", [](const eval::View& s) { return copy_vector(s.viewpoint); },
                             "(3,) the camera's position")
      .def_property_readonly("direction", [](const eval::View& s) { return copy_vector(s.direction); },
                             "(3,) unit, from the object's centre to the camera");
  view_property(view, "points", [](eval::View& s, py::handle o) { return points_view(s.points, o, Access::writeable); },
                "(N, 3) what the camera saw");
  view_property(view, "normals", [](eval::View& s, py::handle o) { return points_view(s.normals, o, Access::writeable); },
                "(N, 3) unit surface normals (meshes), or (0, 3) for clouds");
}

}  // namespace

void bind_types(py::module_& m) {
  bind_mesh(m);
  bind_frame(m);
  bind_shape_space(m);
  bind_model(m);
  bind_registration_result(m);
  bind_cpd_results(m);
  bind_view(m);
}

}  // namespace partreg::python
