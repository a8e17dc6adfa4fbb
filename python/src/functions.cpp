// The module's functions. Each converts its arrays with the interpreter lock held, then releases the lock
// for the library call (so other Python threads run meanwhile), then wraps the result.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <optional>
#include <variant>

#include "arrays.hpp"
#include "bindings.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/eval/views.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/result_file.hpp"
#include "setting_keywords.hpp"

namespace partreg::python {
namespace {

using Path = std::filesystem::path;
using Release = py::call_guard<py::gil_scoped_release>;
using ModelPtr = std::shared_ptr<core::CategoryModel>;
using ResultPtr = std::shared_ptr<core::RegistrationResult>;

// `threads` as the command line's --threads: all threads counted, 0 = all cores.
int thread_count(int threads) {
  if (threads < 0) throw UsageError("threads must be 0 (all cores) or more, not " + std::to_string(threads));
  return threads;
}

void bind_files(py::module_& m) {
  m.def(
      "read_model",
      [](const Path& path) { return std::make_shared<core::CategoryModel>(io::read_model(path)); },
      py::arg("path"), Release(),
      "Reads a model file (.prm). InputError for a missing file, a file that is not a model, another format "
      "version, truncation or corruption.");
  m.def("write_model", &io::write_model, py::arg("path"), py::arg("model").none(false), Release(),
        "Writes a model file atomically.");
  m.def(
      "read_cloud",
      [](const Path& path, std::size_t mesh_samples, std::uint64_t seed) {
        core::Cloud cloud;
        {
          py::gil_scoped_release release;
          cloud = io::read_as_cloud(path, mesh_samples, seed);
        }
        return owned_points(std::move(cloud.points));
      },
      py::arg("path"), py::arg("mesh_samples") = 3000, py::arg("seed") = 1,
      "Any cloud (PCD, PLY, XYZ; NaN points dropped) or mesh (sampled area-uniformly to mesh_samples points "
      "with seed) as (N, 3) float64 points, the file's frame and units. The defaults are `partreg "
      "register`'s for its OBSERVED argument.");
  m.def(
      "read_mesh", [](const Path& path) { return std::make_shared<core::Mesh>(io::read_mesh(path)); },
      py::arg("path"), Release(), "Reads a triangle mesh (OBJ, PLY, STL, OFF, glTF/GLB, ...).");
  m.def(
      "write_mesh",
      [](const Path& path, const core::Mesh& mesh, py::handle vertex_part) {
        const Eigen::VectorXi part =
            vertex_part.is_none() ? Eigen::VectorXi() : to_indices(vertex_part, "vertex_part");
        py::gil_scoped_release release;
        io::write_mesh(path, mesh, vertex_part.is_none() ? nullptr : &part);
      },
      py::arg("path"), py::arg("mesh"), py::arg("vertex_part") = py::none(),
      "Writes .obj or .ply atomically; a PLY gets an int `part` per vertex when vertex_part (V,) is given.");
  m.def(
      "write_cloud",
      [](const Path& path, py::handle points, py::handle part) {
        core::Cloud cloud{to_points(points, "points"), {}};
        io::PointAttributes attributes;
        if (!part.is_none()) attributes.integers["part"] = to_indices(part, "part");
        py::gil_scoped_release release;
        io::write_cloud_ply(path, cloud, attributes);
      },
      py::arg("path"), py::arg("points"), py::arg("part") = py::none(),
      "Writes a binary PLY cloud atomically, with an int `part` per point when part (N,) is given.");
  m.def("read_frames", &io::read_frames_file, py::arg("path"),
        "Frames (name, position, rotation) from a partreg-frames JSON file.");
  m.def("write_frames", &io::write_frames_file, py::arg("path"), py::arg("frames"),
        "Writes frames atomically.");
}

void bind_training(py::module_& m) {
  const io::DatasetOptions dataset;
  // The docstring lists every keyword from the table, so help(partreg.train) cannot go out of date.
  const std::string train_doc =
      "Trains a category from a folder of pose-aligned instances, as `partreg train`. labels: a labels file "
      "giving the canonical its parts, or a list of them (as train --labels: each labels its own instance, "
      "the first's is the canonical); canonical: the instance to use as canonical (default: automatic); "
      "samples and seed: surface samples per mesh instance and their seed (--samples, --seed); threads: as "
      "--threads, all counted, 0 = all cores. Keyword arguments are the training options of `partreg train` "
      "('-' as '_', lambda_ for --lambda, same defaults; lengths normalised: the canonical's diagonal is 1). "
      "UsageError for an unknown keyword or a value out of range, naming the keyword."
      "\n\nKeywords (default, help):" +
      training_keywords_doc();
  m.def(
      "train",
      [](const Path& folder, std::optional<std::variant<Path, std::vector<Path>>> labels,
         std::optional<std::string> canonical, int samples, std::uint64_t seed, int threads,
         const py::kwargs& keywords) {
        core::TrainingSettings settings = training_settings(keywords);
        settings.canonical = canonical;
        py::gil_scoped_release release;
        const core::ThreadBudget budget(thread_count(threads));
        const io::DatasetOptions options{samples, seed};
        io::Dataset read = io::read_dataset(folder, options);
        if (labels) {
          const std::vector<Path> files = std::holds_alternative<Path>(*labels)
                                              ? std::vector<Path>{std::get<Path>(*labels)}
                                              : std::get<std::vector<Path>>(*labels);
          settings.canonical = io::apply_labels_files(read, files, canonical.value_or(""), options);
        }
        return std::make_shared<core::CategoryModel>(
            core::train_category(read.name, read.instances, read.part_names, settings));
      },
      py::arg("dataset_dir"), py::kw_only(), py::arg("labels") = py::none(), py::arg("canonical") = py::none(),
      py::arg("samples") = dataset.points_per_instance, py::arg("seed") = dataset.seed, py::arg("threads") = 0,
      train_doc.c_str());  // pybind11 copies the text
  m.def("training_defaults", &training_defaults,
        "Every training keyword of train() with its default (the command line's).");
  m.def("training_options", &training_options,
        "Every training keyword: keyword, option (the command line's flag), value (its form), help (with "
        "units), default.");
}

// register()'s `init`: None, an earlier RegistrationResult (its first fit's pose and latent) or a (4, 4)
// T_observed_canonical.
std::optional<core::WarmStart> warm_start(py::handle init) {
  if (init.is_none()) return std::nullopt;
  if (py::isinstance<core::RegistrationResult>(init))
    return core::warm_start_of(init.cast<const core::RegistrationResult&>());
  return core::WarmStart{to_matrix(init, 4, 4, "init"), {}};
}

void bind_registration(py::module_& m) {
  // The docstring lists every keyword from the table, so help(partreg.register) cannot go out of date.
  const std::string register_doc =
      "Registers the model to observed points (N, 3) float64 (data units, any frame near the category's). "
      "Keyword arguments are the registration options of `partreg register` ('-' as '_', same defaults): a "
      "bool "
      "for a flag, a number, a name, or 3 numbers (viewpoint, up; None for no viewpoint). InputError for "
      "fewer "
      "than 10 finite points, NaN points or an observation wildly out of scale; UsageError for a bad setting "
      "or "
      "a part-based variant on a model without parts. threads: as --threads, all counted, 0 = all cores. "
      "init: a warm start, an earlier RegistrationResult (its pose and latent) or a (4, 4) "
      "T_observed_canonical; the pose search then runs only when the fit from it scores above warm_limit."
      "\n\nKeywords (default, help):" +
      registration_keywords_doc();
  m.def(
      "register",
      [](const ModelPtr& model, py::handle points, int threads, py::handle init, const py::kwargs& keywords) {
        const core::RegistrationSettings settings = registration_settings(keywords);
        const core::Points observed = to_points(points, "points");
        const std::optional<core::WarmStart> start = warm_start(init);
        py::gil_scoped_release release;
        const core::ThreadBudget budget(thread_count(threads));
        return std::make_shared<core::RegistrationResult>(
            start ? core::register_observation(*model, observed, settings, *start)
                  : core::register_observation(*model, observed, settings));
      },
      py::arg("model").none(false), py::arg("points"), py::kw_only(), py::arg("threads") = 0,
      py::arg("init") = py::none(), register_doc.c_str());  // pybind11 copies the text
  m.def(
      "track",
      [](const ModelPtr& model, const py::sequence& frames, int threads, py::handle init,
         const py::kwargs& keywords) {
        const core::RegistrationSettings settings = registration_settings(keywords);
        std::vector<core::Points> clouds;
        for (std::size_t i = 0; i < frames.size(); ++i)
          clouds.push_back(to_points(frames[i], "frames[" + std::to_string(i) + "]"));
        const std::optional<core::WarmStart> start = warm_start(init);
        std::vector<core::RegistrationResult> results;
        {
          py::gil_scoped_release release;
          const core::ThreadBudget budget(thread_count(threads));
          results = core::register_sequence(*model, clouds, settings, start);
        }
        std::vector<ResultPtr> out;
        for (core::RegistrationResult& result : results)
          out.push_back(std::make_shared<core::RegistrationResult>(std::move(result)));
        return out;
      },
      py::arg("model").none(false), py::arg("frames"), py::kw_only(), py::arg("threads") = 0,
      py::arg("init") = py::none(),
      "Registers a sequence of observations (a stream's frames, each (N, 3) float64) in order: the first from "
      "init (or the pose search), every later one warm from the frame before, the search running only where "
      "the warm fit scores above warm_limit. Returns one RegistrationResult per frame: its seconds, "
      "stage_seconds, start ('searched', 'warm' or 'warm_lost') and warm_score say what each frame cost and "
      "whether the warm start held. Keywords as register().");
  m.def("registration_defaults", &registration_defaults,
        "Every registration keyword of register() with its default (the command line's).");
  m.def("registration_options", &registration_options,
        "Every registration keyword: keyword, option (the command line's flag), value (its form), help (with "
        "units), default.");
  m.def(
      "deform_mesh",
      [](const ModelPtr& model, const ResultPtr& result) {
        return std::make_shared<core::Mesh>(core::deform_mesh(*model, *result));
      },
      Release(), py::arg("model").none(false), py::arg("result").none(false),
      "The canonical mesh deformed into the observed frame (data units, same faces).");
  m.def(
      "mesh_stretch",
      [](const ModelPtr& model, const ResultPtr& result) { return core::mesh_stretch(*model, *result); },
      Release(), py::arg("model").none(false), py::arg("result").none(false),
      "How far the registration stretched the canonical mesh: the largest ratio of an edge's length in "
      "deform_mesh to its canonical length (0 for a model without a mesh), as `partreg register` prints it.");
  m.def(
      "deform_points",
      [](const ModelPtr& model, const ResultPtr& result, py::handle points) {
        const core::Points canonical_points = to_points(points, "points");
        core::Points moved;
        {
          py::gil_scoped_release release;
          moved = core::deform_points(*model, *result, canonical_points);
        }
        return owned_points(std::move(moved));
      },
      py::arg("model").none(false), py::arg("result").none(false), py::arg("points"),
      "Moves points (N, 3) given in the canonical data frame into the observed frame as the registration "
      "moved the canonical.");
  m.def(
      "transfer_frames",
      [](const ModelPtr& model, const ResultPtr& result, const std::vector<core::Frame>& frames) {
        return core::transfer_frames(*model, *result, frames);
      },
      Release(), py::arg("model").none(false), py::arg("result").none(false), py::arg("frames"),
      "Frames attached to the canonical (category's data frame) carried into the observed frame.");
}

// CPD with the command line's names and defaults: the non-rigid settings' values serve every mode.
py::object run_cpd(const core::Points& source, const core::Points& target, const std::string& mode,
                   const py::kwargs& keywords) {
  core::NonrigidCpdSettings s;
  bool scale = false, exact = false;
  std::optional<int> coarse_points;  // unset: each mode's default
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    if (name == "beta")
      s.beta = value.cast<double>();
    else if (name == "lambda_" || name == "lambda")
      s.lambda = value.cast<double>();
    else if (name == "w")
      s.outlier_weight = value.cast<double>();
    else if (name == "tolerance")
      s.tolerance = value.cast<double>();
    else if (name == "max_iterations")
      s.max_iterations = value.cast<int>();
    else if (name == "scale")
      scale = value.cast<bool>();
    else if (name == "exact")
      exact = value.cast<bool>();
    else if (name == "coarse_points")
      coarse_points = value.cast<int>();
    else
      throw UsageError("unknown cpd setting '" + name +
                       "'; known: beta lambda_ w tolerance max_iterations scale exact coarse_points");
  }
  py::gil_scoped_release release;
  if (mode == "rigid") {
    core::RigidCpdSettings settings;
    settings.outlier_weight = s.outlier_weight;
    settings.tolerance = s.tolerance;
    settings.max_iterations = s.max_iterations;
    settings.estimate_scale = scale;
    settings.coarse_points = coarse_points.value_or(settings.coarse_points);
    auto result = std::make_shared<core::RigidCpdResult>(core::register_rigid(source, target, settings));
    py::gil_scoped_acquire acquire;
    return py::cast(result);
  }
  if (mode == "affine") {
    core::AffineCpdSettings settings;
    settings.outlier_weight = s.outlier_weight;
    settings.tolerance = s.tolerance;
    settings.max_iterations = s.max_iterations;
    settings.coarse_points = coarse_points.value_or(settings.coarse_points);
    auto result = std::make_shared<core::AffineCpdResult>(core::register_affine(source, target, settings));
    py::gil_scoped_acquire acquire;
    return py::cast(result);
  }
  if (mode != "nonrigid") throw UsageError("mode must be rigid, affine or nonrigid, not '" + mode + "'");
  if (exact) s.solver = core::NonrigidCpdSettings::Solver::exact;
  s.coarse_points = coarse_points.value_or(s.coarse_points);
  auto result = std::make_shared<core::NonrigidCpdResult>(core::register_nonrigid(source, target, s));
  py::gil_scoped_acquire acquire;
  return py::cast(result);
}

void bind_cpd(py::module_& m) {
  m.def(
      "cpd",
      [](py::handle source, py::handle target, const std::string& mode, const py::kwargs& keywords) {
        return run_cpd(to_points(source, "source"), to_points(target, "target"), mode, keywords);
      },
      py::arg("source"), py::arg("target"), py::arg("mode") = "nonrigid",
      "Coherent Point Drift of source (M, 3) onto target (N, 3), as `partreg cpd`: mode rigid | affine | "
      "nonrigid; settings beta=2 (normalised length: target diagonal 1), lambda_=2, w=0.1 (outlier weight), "
      "tolerance=1e-5, max_iterations=150, scale=False (rigid), exact=False (nonrigid exact solver), "
      "coarse_points (fast path's first subsets: rigid and affine 1000, nonrigid 4000; 0 = none).");
}

void bind_evaluation(py::module_& m) {
  m.def("sphere_directions", &eval::sphere_directions, py::arg("count") = 42,
        "count unit directions from an icosphere (12, 42, 162, ...); UsageError for another count.");
  m.def(
      "views",
      [](py::handle geometry, int count, int width, int height, double fov_degrees, double margin,
         int threads) {
        const eval::CameraSettings camera{width, height, fov_degrees, margin};
        eval::check_camera(camera);  // before the scene is built: Embree aborts on a degenerate camera
        const bool is_mesh = py::isinstance<core::Mesh>(geometry);
        const core::Mesh mesh = is_mesh ? geometry.cast<core::Mesh>() : core::Mesh{};
        const core::Points cloud = is_mesh ? core::Points() : to_points(geometry, "geometry");
        py::gil_scoped_release release;
        const core::ThreadBudget budget(thread_count(threads));
        const eval::ViewCaster caster = is_mesh ? eval::ViewCaster(mesh) : eval::ViewCaster(cloud);
        std::vector<std::shared_ptr<eval::View>> views;
        for (const Eigen::Vector3d& direction : eval::sphere_directions(count))
          views.push_back(std::make_shared<eval::View>(caster.cast(direction, camera)));
        return views;
      },
      py::arg("geometry"), py::arg("count") = 42, py::arg("width") = eval::CameraSettings{}.width,
      py::arg("height") = eval::CameraSettings{}.height,
      py::arg("fov_degrees") = eval::CameraSettings{}.fov_degrees,
      py::arg("margin") = eval::CameraSettings{}.margin, py::arg("threads") = 0,
      "Partial views of a Mesh or a cloud (N, 3) as `partreg views` casts them: a depth camera (width x "
      "height "
      "pixels, vertical field of view in degrees) at each of count icosphere directions; object frame and "
      "units.");
  m.def(
      "measure_errors",
      [](py::handle deformed, py::handle part, const std::vector<std::string>& part_names, py::handle truth,
         std::optional<double> diagonal, py::handle truth_part) {
        const core::Points d = to_points(deformed, "deformed"), t = to_points(truth, "truth");
        const Eigen::VectorXi p = to_indices(part, "part");
        const std::optional<Eigen::VectorXi> tp =
            truth_part.is_none() ? std::nullopt : std::optional(to_indices(truth_part, "truth_part"));
        py::gil_scoped_release release;
        const core::TruthErrors e =
            core::measure_against_truth(d, p, part_names, t, diagonal ? *diagonal : core::truth_diagonal(t),
                                        nullptr, tp ? &*tp : nullptr);
        py::gil_scoped_acquire acquire;
        // The keys and values of the result JSON's truth figures (io::truth_errors_json): one list of them.
        return py::module_::import("json").attr("loads")(io::truth_errors_json(e).dump());
      },
      py::arg("deformed"), py::arg("part"), py::arg("part_names"), py::arg("truth"),
      py::arg("diagonal") = py::none(), py::arg("truth_part") = py::none(),
      "Every error figure of deformed points (M, 3; part (M,) indexing part_names) against a dense sample of "
      "the true instance (N, 3), same frame and data units (core/geometry/truth_errors.hpp, the one home of "
      "them): eq5 "
      "and reverse_eq5 in data units squared, chamfer in data units, *_per_diagonal divided by D, "
      "*_per_diagonal2 by D^2; D is `diagonal` or, when omitted, the truth's bounding-box diagonal. With "
      "truth_part (N,) indexing part_names, also each part against the same part of the truth "
      "(own_part_rms_per_diagonal, and its mean over parts).");
}

}  // namespace

void bind_functions(py::module_& m) {
  bind_files(m);
  bind_training(m);
  bind_registration(m);
  bind_cpd(m);
  bind_evaluation(m);
}

}  // namespace partreg::python
