// Grasps from Python: the Gripper and Grasp classes, reading and writing grasps files, sampling, the gripper
// test, and carrying grasps through a registration (transfer and re-seat), numpy in and out.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/transfer/grasp.hpp"
#include "partreg/eval/gripper.hpp"
#include "partreg/io/grasps_file.hpp"

namespace partreg::python {
namespace {

namespace py = pybind11;
using Release = py::call_guard<py::gil_scoped_release>;
using ModelPtr = std::shared_ptr<core::CategoryModel>;
using ResultPtr = std::shared_ptr<core::RegistrationResult>;

core::Mesh mesh_of(py::handle vertices, py::handle faces) {
  core::Mesh mesh;
  mesh.vertices = to_points(vertices, "vertices");
  mesh.faces = to_faces(faces, "faces");
  return mesh;
}

double diagonal_of(const core::Points& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

py::dict check_dict(const eval::GraspCheck& check, const core::Gripper& gripper) {
  py::dict out;
  out["holds"] = check.holds;
  out["reason"] = check.reason;
  out["width"] = check.width;
  out["angles_degrees"] = py::make_tuple(check.angles_degrees[0], check.angles_degrees[1]);
  out["collides"] = check.collides;
  out["quality"] = eval::grasp_quality(check, gripper);
  return out;
}

void bind_classes(py::module_& m) {
  py::class_<core::Gripper>(m, "Gripper", "A parallel-jaw gripper (docs/grasps.md).")
      .def(py::init([](double max_aperture, double pad_size, double finger_depth, double friction, bool relative) {
             core::Gripper gripper{max_aperture, pad_size, finger_depth, friction, relative};
             core::validate(gripper);
             return gripper;
           }),
           py::arg("max_aperture"), py::arg("pad_size") = core::Gripper{}.pad_size,
           py::arg("finger_depth") = core::Gripper{}.finger_depth, py::arg("friction") = core::Gripper{}.friction,
           py::arg("relative_to_diagonal") = false,
           "Lengths in data units, or fractions of the object's diagonal with relative_to_diagonal.")
      .def_readonly("max_aperture", &core::Gripper::max_aperture)
      .def_readonly("pad_size", &core::Gripper::pad_size)
      .def_readonly("finger_depth", &core::Gripper::finger_depth)
      .def_readonly("friction", &core::Gripper::friction)
      .def_readonly("relative_to_diagonal", &core::Gripper::relative);
  py::class_<core::Grasp>(m, "Grasp", "A parallel-jaw grasp: x closing axis, z approach (docs/grasps.md).")
      .def(py::init([](const std::string& name, py::handle position, py::handle rotation, double width,
                       const std::string& part, double quality) {
             core::Grasp grasp;
             grasp.name = name, grasp.part = part, grasp.width = width, grasp.quality = quality;
             grasp.position = to_matrix(position, 3, 1, "position").col(0);
             grasp.rotation = to_matrix(rotation, 3, 3, "rotation");
             return grasp;
           }),
           py::arg("name"), py::arg("position"), py::arg("rotation"), py::arg("width"), py::arg("part") = "",
           py::arg("quality") = 0.0)
      .def_readonly("name", &core::Grasp::name)
      .def_readonly("part", &core::Grasp::part)
      .def_readonly("width", &core::Grasp::width)
      .def_readonly("quality", &core::Grasp::quality)
      .def_property_readonly("position", [](const core::Grasp& g) { return copy_vector(g.position); })
      .def_property_readonly("rotation", [](const core::Grasp& g) { return copy_matrix(g.rotation); });
}

}  // namespace

void bind_grasps(py::module_& m) {
  bind_classes(m);
  m.def(
      "read_grasps",
      [](const std::filesystem::path& path) {
        io::GraspsFile file = io::read_grasps_file(path);
        return py::make_tuple(file.grasps, file.gripper ? py::cast(*file.gripper) : py::none());
      },
      py::arg("path"), "(grasps, gripper or None) from a grasps file.");
  m.def(
      "write_grasps",
      [](const std::filesystem::path& path, const std::vector<core::Grasp>& grasps,
         std::optional<core::Gripper> gripper) { io::write_grasps_file(path, grasps, gripper); },
      Release(), py::arg("path"), py::arg("grasps"), py::arg("gripper") = py::none());
  m.def(
      "sample_grasps",
      [](py::handle vertices, py::handle faces, const core::Gripper& gripper, int count, std::uint64_t seed) {
        const core::Mesh mesh = mesh_of(vertices, faces);
        py::gil_scoped_release release;
        return eval::sample_grasps(mesh, gripper.in_units(diagonal_of(mesh.vertices)), count, seed);
      },
      py::arg("vertices"), py::arg("faces"), py::arg("gripper"), py::arg("count") = 50, py::arg("seed") = 1,
      "Antipodal grasps the gripper holds on a mesh (vertices (N, 3), faces (F, 3)), ranked by quality.");
  m.def(
      "check_grasps",
      [](py::handle vertices, py::handle faces, const std::vector<core::Grasp>& grasps, const core::Gripper& gripper) {
        const core::Mesh mesh = mesh_of(vertices, faces);
        const core::Gripper absolute = gripper.in_units(diagonal_of(mesh.vertices));
        const eval::MeshRays object(mesh);
        py::list out;
        for (const core::Grasp& grasp : grasps) out.append(check_dict(eval::check_grasp(object, grasp, absolute), absolute));
        return out;
      },
      py::arg("vertices"), py::arg("faces"), py::arg("grasps"), py::arg("gripper"),
      "The gripper test of each grasp on a mesh: a dict per grasp (holds, reason, width, angles_degrees, "
      "collides, quality).");
  m.def(
      "transfer_grasps",
      [](const ModelPtr& model, const ResultPtr& result, const std::vector<core::Grasp>& grasps,
         const core::Gripper& gripper, py::handle observed) {
        const std::optional<core::Points> seen =
            observed.is_none() ? std::nullopt : std::optional(to_points(observed, "observed"));
        py::gil_scoped_release release;
        const core::Gripper absolute = gripper.in_units(model->observed_diagonal());
        const std::vector<core::Grasp> carried = core::transfer_grasps(*model, *result, grasps, absolute);
        if (model->canonical_mesh.faces.rows() == 0) return carried;
        const eval::MeshRays believed(core::deform_mesh(*model, *result));
        return eval::reseat_grasps(believed, seen ? &*seen : nullptr, carried, absolute);
      },
      py::arg("model").none(false), py::arg("result").none(false), py::arg("grasps"), py::arg("gripper"),
      py::arg("observed") = py::none(),
      "Grasps on the canonical carried onto the registered object, re-seated on its deformed mesh (and on "
      "`observed` points where given) and ranked by quality (as `partreg register --grasps`).");
}

}  // namespace partreg::python
