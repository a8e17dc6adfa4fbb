#pragma once
/// \file
/// Small synthetic inputs for the GUI tests: a mug mesh file (body and handle merged, handle faces known)
/// and a small trained mug model, written once per process into a temporary folder.

#include <filesystem>
#include <string>
#include <vector>

#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"

namespace partreg::testing {

/// The folder is per build of the test executable (its modification time, in the folder's name): the
/// executable is relinked whenever the libraries that train the fixture model change, so a model cached by
/// an earlier build, trained by other code or other defaults, is never reused (it once kept three stale
/// baselines passing on one machine only).
inline std::filesystem::path ui_fixture_folder() {
  std::error_code error;
  const auto built = std::filesystem::last_write_time("/proc/self/exe", error);
  const auto stamp = error ? 0 : built.time_since_epoch().count();
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("partreg_ui_fixtures_v" + std::to_string(io::kModelFormatVersion) +
                                                "_" + std::to_string(stamp));
  std::filesystem::create_directories(folder);
  return folder;
}

/// The parts of a synthetic mug merged into one mesh; `face_part` gets the part of each face.
inline core::Mesh merged_mug(int index, Eigen::VectorXi* face_part = nullptr,
                             Eigen::VectorXi* vertex_part = nullptr) {
  const core::SyntheticInstance mug = core::make_synthetic_instance(core::SyntheticCategory::mug, 7, index);
  core::Mesh merged;
  std::vector<int> faces_of, vertices_of;
  for (std::size_t p = 0; p < mug.parts.size(); ++p) {
    const core::Mesh& part = mug.parts[p].mesh;
    const Eigen::Index v0 = merged.vertices.rows(), f0 = merged.faces.rows();
    merged.vertices.conservativeResize(v0 + part.vertices.rows(), 3);
    merged.vertices.bottomRows(part.vertices.rows()) = part.vertices;
    merged.faces.conservativeResize(f0 + part.faces.rows(), 3);
    merged.faces.bottomRows(part.faces.rows()) = part.faces.array() + static_cast<int>(v0);
    faces_of.insert(faces_of.end(), static_cast<std::size_t>(part.faces.rows()), static_cast<int>(p));
    vertices_of.insert(vertices_of.end(), static_cast<std::size_t>(part.vertices.rows()),
                       static_cast<int>(p));
  }
  if (face_part)
    *face_part = Eigen::Map<Eigen::VectorXi>(faces_of.data(), static_cast<Eigen::Index>(faces_of.size()));
  if (vertex_part)
    *vertex_part =
        Eigen::Map<Eigen::VectorXi>(vertices_of.data(), static_cast<Eigen::Index>(vertices_of.size()));
  return merged;
}

/// mug.obj: synthetic mug 0 (body faces first, then the handle's).
inline std::filesystem::path mug_mesh_path() {
  const std::filesystem::path path = ui_fixture_folder() / "mug.obj";
  if (!std::filesystem::exists(path)) io::write_mesh(path, merged_mug(0));
  return path;
}

/// A dataset folder `name` of `count` synthetic mug meshes mug_0.obj, mug_1.obj, ... (no parts), written
/// afresh.
inline std::filesystem::path mug_dataset(const std::string& name, int count) {
  const std::filesystem::path folder = ui_fixture_folder() / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  for (int i = 0; i < count; ++i)
    io::write_mesh(folder / ("mug_" + std::to_string(i) + ".obj"), merged_mug(i));
  return folder;
}

/// observed.ply: a surface sample of synthetic mug 5 (not in the model's training set).
inline std::filesystem::path observed_cloud_path() {
  const std::filesystem::path path = ui_fixture_folder() / "observed.ply";
  if (!std::filesystem::exists(path)) {
    const core::SyntheticInstance mug = core::make_synthetic_instance(core::SyntheticCategory::mug, 7, 5);
    core::Cloud cloud;
    cloud.points =
        core::sample_correspondences(core::SyntheticCategory::mug, mug.shape_parameters, 1500, 3).points;
    io::write_cloud_ply(path, cloud);
  }
  return path;
}

/// mug.prm: a small model of 5 synthetic mugs (200 canonical points, 3 latent dimensions).
inline std::filesystem::path small_model_path() {
  const std::filesystem::path path = ui_fixture_folder() / "mug.prm";
  if (std::filesystem::exists(path)) return path;
  std::vector<core::TrainingInstance> instances;
  for (int i = 0; i < 5; ++i) {
    const core::SyntheticInstance mug = core::make_synthetic_instance(core::SyntheticCategory::mug, 7, i);
    const core::SurfaceSamples samples =
        core::sample_correspondences(core::SyntheticCategory::mug, mug.shape_parameters, 800, 3);
    core::TrainingInstance instance;
    instance.name = mug.name;
    instance.points = samples.points;
    instance.part = samples.part;
    instance.mesh = merged_mug(i, nullptr, &instance.mesh_vertex_part);
    instances.push_back(std::move(instance));
  }
  core::TrainingSettings settings;
  settings.canonical_points = 200;
  settings.target_points = 400;
  settings.latent_dimensions = 3;
  settings.canonical = instances.front().name;
  const core::CategoryModel model =
      core::train_category("mugs", instances, core::part_names(core::SyntheticCategory::mug), settings);
  io::write_model(path, model);
  return path;
}

}  // namespace partreg::testing
