// Every output is what its name says, written where it is asked without destroying what is not
// partreg's (devices, FIFOs, links), and nothing half-written or stale is left behind.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <fstream>
#include <thread>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/output_format.hpp"
#include "support/temp_dir.hpp"

namespace partreg::io {
namespace {

core::Cloud small_cloud(int n) {
  core::Cloud cloud;
  cloud.points = core::Points::Random(n, 3);
  cloud.normals = cloud.points.rowwise().normalized();
  return cloud;
}

PointAttributes parts_and_u(int n) {
  PointAttributes attributes;
  attributes.integers["part"] = Eigen::VectorXi::LinSpaced(n, 0, n - 1).unaryExpr([](int i) { return i % 3; });
  attributes.reals["u"] = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  return attributes;
}

TEST(Outputs, PcdIsWrittenThroughPclAndReadsBackWithItsPartField) {
  testing::TempDir dir;
  const core::Cloud cloud = small_cloud(50);
  write_cloud(dir / "c.pcd", cloud, parts_and_u(50));
  std::ifstream in(dir / "c.pcd");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first.rfind("# .PCD", 0), 0u) << "not PCD bytes: " << first;
  const CloudFile read = read_cloud_file(dir / "c.pcd");  // through pcl::PCDReader
  ASSERT_EQ(read.cloud.points.rows(), 50);
  EXPECT_LT((read.cloud.points - cloud.points).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((read.cloud.normals - cloud.normals).cwiseAbs().maxCoeff(), 1e-6);
  ASSERT_TRUE(read.attributes.integers.count("part"));
  EXPECT_EQ(read.attributes.integers.at("part"), parts_and_u(50).integers.at("part"));
  EXPECT_NEAR(read.attributes.reals.at("u")[49], 1.0, 1e-6);
}

TEST(Outputs, VtpCloudsAndMeshesKeepEveryPointArray) {
  testing::TempDir dir;
  const core::Cloud cloud = small_cloud(40);
  write_cloud(dir / "c.vtp", cloud, parts_and_u(40));
  const CloudFile read = read_cloud_file(dir / "c.vtp");  // through vtkXMLPolyDataReader
  ASSERT_EQ(read.cloud.points.rows(), 40);
  EXPECT_LT((read.cloud.points - cloud.points).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((read.cloud.normals - cloud.normals).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(read.attributes.integers.at("part"), parts_and_u(40).integers.at("part"));
  EXPECT_EQ(read.attributes.reals.at("u"), parts_and_u(40).reals.at("u"));
  EXPECT_FALSE(is_mesh_file(dir / "c.vtp"));

  core::Mesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  PointAttributes arrays;
  arrays.integers["part"] = Eigen::Vector4i(0, 0, 1, 1);
  arrays.reals["displacement_x"] = Eigen::Vector4d(0.1, 0.2, 0.3, 0.4);
  write_mesh(dir / "m.vtp", mesh, arrays);
  EXPECT_TRUE(is_mesh_file(dir / "m.vtp"));
  EXPECT_EQ(read_mesh(dir / "m.vtp").faces, mesh.faces);
  const CloudFile vertices = read_cloud_file(dir / "m.vtp");
  EXPECT_EQ(vertices.attributes.integers.at("part"), arrays.integers.at("part"));
  EXPECT_EQ(vertices.attributes.reals.at("displacement_x"), arrays.reals.at("displacement_x"));
}

// Every format that carries attributes reads back what was written: parts by index and name, normals, and
// per-point integers and reals (PLY clouds in float32, the rest in full precision).
TEST(Outputs, PlyAndVtpRoundTripPartsByNameNormalsAndAttributes) {
  testing::TempDir dir;
  const core::Cloud cloud = small_cloud(30);
  PointAttributes written = parts_and_u(30);
  written.integers["correspondence"] = Eigen::VectorXi::LinSpaced(30, 100, 129);
  written.part_names = {"body", "handle", "spout rim"};  // a name may hold a space
  for (const char* file : {"c.ply", "c_ascii.ply", "c.vtp"}) {
    const bool ascii = std::string(file) == "c_ascii.ply";
    write_cloud(dir / file, cloud, written, ascii ? PlyEncoding::ascii : PlyEncoding::binary);
    const CloudFile read = read_cloud_file(dir / file);
    const double precision = std::string(file) == "c.vtp" ? 1e-12 : 1e-6;
    EXPECT_LT((read.cloud.points - cloud.points).cwiseAbs().maxCoeff(), precision) << file;
    EXPECT_LT((read.cloud.normals - cloud.normals).cwiseAbs().maxCoeff(), precision) << file;
    EXPECT_EQ(read.attributes.integers, written.integers) << file;
    EXPECT_LT((read.attributes.reals.at("u") - written.reals.at("u")).cwiseAbs().maxCoeff(), precision)
        << file;
    EXPECT_EQ(read.attributes.part_names, written.part_names) << file;
  }

  core::Mesh mesh;  // a tetrahedron with its own (made-up) unit normals
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  mesh.normals = (mesh.vertices.rowwise() - Eigen::RowVector3d(0.25, 0.25, 0.25)).rowwise().normalized();
  PointAttributes arrays;
  arrays.integers["part"] = Eigen::Vector4i(0, 0, 1, 1);
  arrays.reals["residual"] = Eigen::Vector4d(0.1, 0.2, 0.3, 0.4);
  arrays.part_names = {"body", "handle"};
  for (const char* file : {"m.ply", "m.vtp"}) {
    write_mesh(dir / file, mesh, arrays);
    const MeshFile read = read_mesh_file(dir / file);
    ASSERT_EQ(read.mesh.vertices.rows(), 4) << file;
    ASSERT_EQ(read.mesh.normals.rows(), 4) << file;
    EXPECT_EQ(read.vertex_attributes.part_names, arrays.part_names) << file;
    // The mesh reader may order the vertices its own way: each is compared with the written one it stands on.
    for (Eigen::Index v = 0; v < 4; ++v) {
      Eigen::Index written = 0;
      (mesh.vertices.rowwise() - read.mesh.vertices.row(v)).rowwise().norm().minCoeff(&written);
      EXPECT_LT((read.mesh.vertices.row(v) - mesh.vertices.row(written)).norm(), 1e-9) << file;
      EXPECT_LT((read.mesh.normals.row(v) - mesh.normals.row(written)).norm(), 1e-8) << file;
      EXPECT_EQ(read.vertex_attributes.integers.at("part")[v], arrays.integers.at("part")[written]) << file;
      EXPECT_NEAR(read.vertex_attributes.reals.at("residual")[v], arrays.reals.at("residual")[written], 1e-9)
          << file;
    }
  }
  // An OBJ keeps the mesh alone: nothing is invented on reading it back.
  write_mesh(dir / "m.obj", mesh, arrays);
  EXPECT_TRUE(read_mesh_file(dir / "m.obj").vertex_attributes.integers.empty());
}

TEST(Outputs, AnExtensionThatPromisesAnotherFormatIsAUsageError) {
  testing::TempDir dir;
  const core::Cloud cloud = small_cloud(5);
  EXPECT_THROW(write_cloud(dir / "p.npz", cloud), UsageError);
  EXPECT_THROW(write_cloud(dir / "p", cloud), UsageError);
  EXPECT_THROW(write_cloud_ply(dir / "p.pcd", cloud), UsageError);  // PLY bytes under a PCD name
  EXPECT_THROW(write_mesh(dir / "m.pcd", core::Mesh{}), UsageError);
  EXPECT_TRUE(dir.entries().empty());
  EXPECT_EQ(output_format("-", OutputKind::json), FileFormat::json);
  EXPECT_EQ(output_format("/dev/null", OutputKind::cloud), FileFormat::ply);
  EXPECT_EQ(output_format(dir / "x.XYZ", OutputKind::cloud), FileFormat::xyz);
  EXPECT_THROW(check_output((dir / "none" / "x.json").string(), OutputKind::json, "--json"), InputError);
  EXPECT_THROW(check_output(dir.path().string() + "/x.txt", OutputKind::json, "--json"), UsageError);
  std::filesystem::create_directories(dir / "folder.json");
  EXPECT_THROW(check_output((dir / "folder.json").string(), OutputKind::json, "--json"), InputError)
      << "a folder is not a file to replace";
}

TEST(Outputs, AFifoIsWrittenDirectlyNotReplaced) {
  testing::TempDir dir;
  const auto fifo = dir / "pipe.xyz";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);
    received.assign(std::istreambuf_iterator<char>(in), {});
  });
  write_cloud(fifo, small_cloud(3));
  reader.join();
  struct stat status {};
  ASSERT_EQ(::lstat(fifo.c_str(), &status), 0);
  EXPECT_TRUE(S_ISFIFO(status.st_mode)) << "the FIFO was replaced by a regular file";
  EXPECT_EQ(std::count(received.begin(), received.end(), '\n'), 3) << received;
  EXPECT_EQ(dir.entries().size(), 1u);
}

TEST(Outputs, ASymbolicLinkIsFollowedAndStays) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "real");
  std::filesystem::create_symlink("real/target.ply", dir / "link.ply");
  write_cloud(dir / "link.ply", small_cloud(7));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.ply"));
  EXPECT_EQ(read_cloud_file(dir / "real" / "target.ply").cloud.points.rows(), 7);
  write_cloud(dir / "link.ply", small_cloud(9));  // an existing target is replaced through the link
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.ply"));
  EXPECT_EQ(read_cloud_file(dir / "link.ply").cloud.points.rows(), 9);
}

TEST(Outputs, AFullDeviceIsAnErrorNamingTheDestination) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this machine";
  try {
    write_cloud("/dev/full", small_cloud(20000));
    ADD_FAILURE() << "writing to /dev/full succeeded";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot write /dev/full"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));
}

// The staging file of a run that was killed (its process is gone) is removed by the next write there.
TEST(Outputs, StaleStagingOfAKilledRunIsCleaned) {
  testing::TempDir dir;
  pid_t dead = 0;
  for (pid_t pid = 4000000; pid > 1000; --pid)
    if (::kill(pid, 0) != 0 && errno == ESRCH) {
      dead = pid;
      break;
    }
  ASSERT_NE(dead, 0);
  const std::string stale = ".out.ply.partial-" + std::to_string(dead) + "-0";
  std::ofstream(dir / stale) << "half";
  const std::string stale_folder = ".views.partial-" + std::to_string(dead);
  std::filesystem::create_directories(dir / stale_folder / "inside");
  const std::string alive = ".out.ply.partial-" + std::to_string(::getpid()) + "-999";
  std::ofstream(dir / alive) << "a write of ours in progress";
  write_cloud(dir / "out.ply", small_cloud(4));
  EXPECT_FALSE(std::filesystem::exists(dir / stale));
  EXPECT_TRUE(std::filesystem::exists(dir / alive)) << "a live process's staging file was removed";
  {
    StagedFolder folder(dir / "views");
    folder.commit();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / stale_folder));
}

// A nearly full disk: a small tmpfs where the machine lets us mount one (root with CAP_SYS_ADMIN).
TEST(Outputs, ADiskFullWriteFailsAndLeavesNothing) {
  testing::TempDir dir;
  const auto mount_point = dir / "small";
  std::filesystem::create_directories(mount_point);
  if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs here (" << std::strerror(errno) << "): disk-full case not run";
  EXPECT_THROW(write_cloud(mount_point / "big.ply", small_cloud(100000)), InputError);
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(mount_point)) left.push_back(entry.path().string());
  ::umount(mount_point.c_str());
  EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
}

}  // namespace
}  // namespace partreg::io
