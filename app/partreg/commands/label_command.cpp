// `partreg label MESH --part NAME --box|--plane|--sphere ...`: assign mesh faces to a part without the GUI.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/output_format.hpp"

namespace partreg::app {
namespace {

struct LabelOptions {
  std::string mesh_path, part, box, plane, sphere, in_path, out_path, rest = "body";
};

core::PartSelector selector_of(const LabelOptions& options) {
  const int given = !options.box.empty() + !options.plane.empty() + !options.sphere.empty();
  if (given != 1) throw UsageError("give exactly one of --box, --plane and --sphere");
  // The library names the value; only the command line knows which flag carried it.
  const auto parse_flag = [](const std::string& flag, auto parse, const std::string& text) {
    try {
      return parse(text);
    } catch (const UsageError& error) {
      throw UsageError(flag + ": " + error.what());
    }
  };
  if (!options.box.empty()) return parse_flag("--box", core::parse_box, options.box);
  if (!options.plane.empty()) return parse_flag("--plane", core::parse_plane, options.plane);
  return parse_flag("--sphere", core::parse_sphere, options.sphere);
}

io::PartLabels starting_labels(const LabelOptions& options, const core::Mesh& mesh) {
  if (!options.in_path.empty()) {
    io::PartLabels labels = io::read_labels_file(options.in_path);
    if (labels.target != io::PartLabels::Target::faces)
      throw InputError(options.in_path + " labels points, not mesh faces");
    io::check_labels_match(labels, static_cast<std::size_t>(mesh.faces.rows()),
                           "faces in " + options.mesh_path);
    return labels;
  }
  io::PartLabels labels;
  labels.source = std::filesystem::path(options.mesh_path).filename().string();
  labels.labels = Eigen::VectorXi::Constant(mesh.faces.rows(), labels.part_index(options.rest));
  return labels;
}

void report(const io::PartLabels& labels, const core::Mesh& mesh) {
  std::vector<double> area(labels.names.size(), 0.0);
  double total = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    const double face_area = 0.5 * (b - a).cross(c - a).norm();
    total += face_area;
    if (labels.labels[f] >= 0) area[static_cast<std::size_t>(labels.labels[f])] += face_area;
  }
  for (std::size_t p = 0; p < labels.names.size(); ++p)
    std::cerr << "part " << labels.names[p] << ": " << (labels.labels.array() == static_cast<int>(p)).count()
              << " faces, " << std::round(1000.0 * area[p] / total) / 10.0 << "% of the area\n";
}

void run_label(const LabelOptions& options) {
  const core::PartSelector selector = selector_of(options);
  if (options.part.empty()) throw UsageError("--part must name a part");
  io::check_output(options.out_path, io::OutputKind::json, "--out");
  const core::Mesh mesh = io::read_mesh(options.mesh_path);
  io::PartLabels labels = starting_labels(options, mesh);
  const std::vector<bool> selected = core::select_faces(mesh, selector);
  if (std::none_of(selected.begin(), selected.end(), [](bool s) { return s; })) {
    const Eigen::RowVector3d low = mesh.vertices.colwise().minCoeff(),
                             high = mesh.vertices.colwise().maxCoeff();
    std::ostringstream bounds;
    bounds << "x [" << low.x() << ", " << high.x() << "], y [" << low.y() << ", " << high.y() << "], z ["
           << low.z() << ", " << high.z() << "]";
    throw InputError("the selector selects no face of " + options.mesh_path + "; the mesh spans " +
                     bounds.str());
  }
  detail_log() << "the selector takes " << std::count(selected.begin(), selected.end(), true) << " of "
               << mesh.faces.rows() << " faces\n";
  const int part = labels.part_index(options.part);
  for (std::size_t f = 0; f < selected.size(); ++f)
    if (selected[f]) labels.labels[static_cast<Eigen::Index>(f)] = part;
  io::write_labels_file(options.out_path, labels);
  report(labels, mesh);
  std::cerr << "wrote " << options.out_path << '\n';
}

}  // namespace

void add_label_command(CLI::App& app) {
  auto o = std::make_shared<LabelOptions>();
  CLI::App* command = app.add_subcommand("label", "Assign mesh faces to a part with a box, plane or sphere");
  command->add_option("MESH", o->mesh_path, "the canonical mesh to label")->required();
  command->add_option("--part", o->part, "part the selected faces get")->required();
  command->add_option("--box", o->box, "X0,Y0,Z0,X1,Y1,Z1: faces whose centroid is inside the box");
  command->add_option("--plane", o->plane, "PX,PY,PZ,NX,NY,NZ: faces on the side the normal points to");
  command->add_option("--sphere", o->sphere, "CX,CY,CZ,R: faces within the ball");
  command->add_option("--in", o->in_path, "start from this labels file (same mesh)");
  command->add_option("--rest", o->rest, "part of every face not yet labelled, when starting afresh")
      ->capture_default_str();
  command->add_option("--out", o->out_path, "labels file to write (JSON)")->required();
  command->callback([o] { run_label(*o); });
}

}  // namespace partreg::app
