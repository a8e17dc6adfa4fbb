#include <gtest/gtest.h>

#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "support/temp_dir.hpp"

namespace partreg::io {
namespace {

core::Mesh tetrahedron() {
  core::Mesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return mesh;
}

TEST(MeshIo, ObjAndPlyRoundTrip) {
  testing::TempDir dir;
  const core::Mesh mesh = tetrahedron();
  const Eigen::VectorXi part = Eigen::Vector4i(0, 0, 1, 1);
  for (const char* name : {"t.obj", "t.ply"}) {
    write_mesh(dir / name, mesh, &part);
    const core::Mesh read = read_mesh(dir / name);
    EXPECT_EQ(read.faces.rows(), 4) << name;
    EXPECT_EQ(read.vertices.rows(), 4) << name;
    EXPECT_TRUE(is_mesh_file(dir / name));
    EXPECT_EQ(read_as_cloud(dir / name, 50, 1).points.rows(), 50);
  }
  EXPECT_THROW(write_mesh(dir / "t.stl", mesh), UsageError);
}

TEST(MeshIo, ReadsStlAndOffThroughAssimp) {
  testing::TempDir dir;
  std::ofstream(dir / "t.off")
      << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(dir / "t.stl")
      << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
         "endloop\nendfacet\nendsolid t\n";
  EXPECT_EQ(read_mesh(dir / "t.off").faces.rows(), 4);
  EXPECT_EQ(read_mesh(dir / "t.stl").faces.rows(), 1);
}

// ShapeNet OBJs name a material library that is not there. Looking for it, assimp opened paths built from
// the parent folders relative to the working directory and failed on a directory ("File read error") when
// the path held "..", as `../shared/data/...` from the repository's root does.
TEST(MeshIo, AnObjWithAMissingMaterialLibraryReadsThroughAPathWithDotDot) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "main");
  std::filesystem::create_directories(dir / "shared" / "data" / "mugs");
  std::filesystem::create_directories(dir / "shared" / "data" / "shared" / "data");  // a folder it tripped on
  std::ofstream(dir / "shared" / "data" / "mugs" / "1a97f3c83016abca21d0de04f408950f.obj")
      << "mtllib material0.mtl\nusemtl material0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir / "main");
  core::Mesh mesh;
  EXPECT_NO_THROW(mesh = read_mesh(dir / "main" / ".." / "shared" / "data" / "mugs" /
                                   "1a97f3c83016abca21d0de04f408950f.obj"));
  EXPECT_NO_THROW(read_mesh(std::filesystem::path("..") / "shared" / "data" / "mugs" /
                            "1a97f3c83016abca21d0de04f408950f.obj"));
  std::filesystem::current_path(before);
  EXPECT_EQ(mesh.faces.rows(), 4);
}

TEST(MeshIo, AMeshWithoutFacesIsRefused) {
  testing::TempDir dir;
  std::ofstream(dir / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_THROW(read_mesh(dir / "points.obj"), InputError);
  EXPECT_THROW(read_mesh(dir / "missing.obj"), InputError);
}

// A small model trained on a synthetic mug category, shared by the model-file tests.
core::CategoryModel small_model() {
  std::vector<core::TrainingInstance> instances;
  for (const auto& synthetic : core::make_synthetic_category(core::SyntheticCategory::mug, 4, 3)) {
    core::TrainingInstance instance;
    instance.name = synthetic.name;
    const auto samples =
        core::sample_correspondences(core::SyntheticCategory::mug, synthetic.shape_parameters, 600, 5);
    instance.points = samples.points;
    instance.part = samples.part;
    instances.push_back(instance);
  }
  core::TrainingSettings settings;
  settings.canonical_points = 200;
  settings.target_points = 300;
  return core::train_category("mugs", instances, {"body", "handle"}, settings);
}

TEST(ModelFile, SavesAndLoadsBitForBit) {
  testing::TempDir dir;
  core::CategoryModel model = small_model();
  model.up = Eigen::Vector3d(0, 0.6, 0.8);  // the category's up axis is kept
  write_model(dir / "m.prm", model);
  const core::CategoryModel read = read_model(dir / "m.prm");
  EXPECT_EQ(read.up, model.up);
  ASSERT_EQ(read.spaces.size(), model.spaces.size());
  EXPECT_EQ(read.canonical, model.canonical);
  EXPECT_EQ(read.canonical_part, model.canonical_part);
  EXPECT_EQ(read.part_names, model.part_names);
  for (std::size_t s = 0; s < model.spaces.size(); ++s) {
    EXPECT_EQ(read.spaces[s].basis, model.spaces[s].basis);
    EXPECT_EQ(read.spaces[s].kernel_basis, model.spaces[s].kernel_basis);
    EXPECT_EQ(read.spaces[s].variances, model.spaces[s].variances);
    EXPECT_EQ(read.spaces[s].canonical, model.spaces[s].canonical);
    EXPECT_EQ(read.spaces[s].training_latents, model.spaces[s].training_latents);
  }
  EXPECT_EQ(read.training.instances, model.training.instances);
  EXPECT_EQ(read.training.min_part_points, 150);  // the sampling used: the default floor per part
  EXPECT_EQ(read.training.canonical_points, model.canonical.rows());
  EXPECT_EQ(read.training.seam_weight, model.training.seam_weight);
  ASSERT_EQ(read.training.seam_weight_trials.size(), model.training.seam_weight_trials.size());
  for (std::size_t c = 0; c < model.training.seam_weight_trials.size(); ++c) {
    EXPECT_EQ(read.training.seam_weight_trials[c].weight, model.training.seam_weight_trials[c].weight);
    EXPECT_EQ(read.training.seam_weight_trials[c].error, model.training.seam_weight_trials[c].error);
  }
  EXPECT_EQ(read.training_weights, model.training_weights);
  EXPECT_EQ(read.training_weights.rows(), 4);
  // Writing what was read gives the same bytes.
  write_model(dir / "again.prm", read);
  std::ifstream a(dir / "m.prm", std::ios::binary), b(dir / "again.prm", std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
            std::string(std::istreambuf_iterator<char>(b), {}));
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void expect_refused(const std::filesystem::path& path, const std::string& words) {
  try {
    read_model(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

TEST(ModelFile, RefusesOtherVersionsTruncationCorruptionAndOtherFiles) {
  testing::TempDir dir;
  write_model(dir / "m.prm", small_model());
  const std::string bytes = read_bytes(dir / "m.prm");
  std::ofstream(dir / "truncated.prm", std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  std::string corrupted = bytes;
  corrupted[corrupted.size() - 50] ^= 0x5a;
  std::ofstream(dir / "corrupted.prm", std::ios::binary) << corrupted;
  std::string other_version = bytes;
  const std::string version = "\"format_version\":" + std::to_string(kModelFormatVersion);
  const auto at = other_version.find(version);
  ASSERT_NE(at, std::string::npos);
  other_version.replace(at, version.size(), "\"format_version\":7");
  std::ofstream(dir / "version.prm", std::ios::binary) << other_version;
  std::ofstream(dir / "text.prm") << "hello\n";
  expect_refused(dir / "truncated.prm", "truncated");
  expect_refused(dir / "corrupted.prm", "corrupted");
  expect_refused(dir / "version.prm", "format version 7");
  // A version 1 file (before the training instances were kept) gets the same clear refusal.
  std::string version_1 = bytes;
  version_1.replace(at, version.size(), "\"format_version\":1");
  std::ofstream(dir / "version_1.prm", std::ios::binary) << version_1;
  expect_refused(dir / "version_1.prm", "format version 1");
  expect_refused(dir / "text.prm", "not a partreg model");
  expect_refused(dir / "missing.prm", "missing.prm");
}

TEST(Dataset, BadFoldersAreRefusedWithTheFolderNamed) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "empty");
  std::filesystem::create_directories(dir / "one/a");
  write_mesh(dir / "one/a/body.obj", tetrahedron());
  for (const char* instance : {"a", "b"}) std::filesystem::create_directories(dir / "mixed" / instance);
  write_mesh(dir / "mixed/a/body.obj", tetrahedron());
  write_mesh(dir / "mixed/b/lid.obj", tetrahedron());
  EXPECT_THROW(read_dataset(dir / "empty"), InputError);
  EXPECT_THROW(read_dataset(dir / "one"), InputError);
  try {
    read_dataset(dir / "mixed");
    ADD_FAILURE() << "part folders with different parts were accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("differ"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace partreg::io
