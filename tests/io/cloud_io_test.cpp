#include "partreg/io/cloud_io.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "support/temp_dir.hpp"

namespace partreg::io {
namespace {

core::Cloud small_cloud() {
  core::Cloud cloud;
  cloud.points.resize(4, 3);
  cloud.points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.5, -2;
  cloud.normals.resize(4, 3);
  cloud.normals << 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return cloud;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(CloudIo, PlyRoundTripsBinaryAndAsciiWithNormalsAndAttributes) {
  testing::TempDir dir;
  const core::Cloud cloud = small_cloud();
  PointAttributes attributes;
  attributes.integers["part"] = Eigen::Vector4i(0, 1, 1, 2);
  attributes.reals["u"] = Eigen::Vector4d(0.5, 0.25, 0.125, 1.0);
  for (bool binary : {true, false}) {
    const auto path = dir / (binary ? "b.ply" : "a.ply");
    write_cloud_ply(path, cloud, attributes, binary);
    const CloudFile read = read_cloud_file(path);
    EXPECT_TRUE(read.cloud.points.isApprox(cloud.points, 1e-6));
    EXPECT_TRUE(read.cloud.normals.isApprox(cloud.normals, 1e-6));
    EXPECT_EQ(read.attributes.integers.at("part"), attributes.integers["part"]);
    EXPECT_TRUE(read.attributes.reals.at("u").isApprox(attributes.reals["u"], 1e-6));
    EXPECT_FALSE(is_mesh_file(path));
  }
}

TEST(CloudIo, ReadsBigEndianPly) {
  testing::TempDir dir;
  std::string data =
      "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty "
      "float z\nend_header\n";
  for (float value : {1.0f, 2.0f, 3.0f, -4.0f, 5.5f, 6.0f}) {
    char bytes[4];
    std::memcpy(bytes, &value, 4);
    std::reverse(bytes, bytes + 4);
    data.append(bytes, 4);
  }
  write_text(dir / "be.ply", data);
  const CloudFile read = read_cloud_file(dir / "be.ply");
  ASSERT_EQ(read.cloud.points.rows(), 2);
  EXPECT_DOUBLE_EQ(read.cloud.points(1, 0), -4.0);
  EXPECT_DOUBLE_EQ(read.cloud.points(1, 1), 5.5);
}

TEST(CloudIo, ReadsXyzAndDropsNaNPoints) {
  testing::TempDir dir;
  write_text(dir / "c.xyz", "# a comment\n0 0 0\n1 2 3\nnan 0 0\n4 5 6\n");
  const CloudFile read = read_cloud_file(dir / "c.xyz");
  EXPECT_EQ(read.cloud.points.rows(), 3);
  EXPECT_EQ(read.dropped_non_finite, 1u);
  EXPECT_DOUBLE_EQ(read.cloud.points(2, 2), 6.0);
}

// PCD writers by hand: ascii, binary, and binary_compressed with an LZF stream made only of literal runs
// (a valid LZF encoding), so the test needs no PCL of its own.
std::string pcd_header(const std::string& data, int points) {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " +
         std::to_string(points) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(points) +
         "\nDATA " + data + "\n";
}

std::string lzf_literals(const std::string& raw) {
  std::string out;
  for (std::size_t i = 0; i < raw.size(); i += 32) {
    const std::size_t run = std::min<std::size_t>(32, raw.size() - i);
    out.push_back(static_cast<char>(run - 1));
    out.append(raw, i, run);
  }
  return out;
}

TEST(CloudIo, ReadsPcdAsciiBinaryAndBinaryCompressed) {
  testing::TempDir dir;
  const std::vector<float> xyz = {0, 0, 0, 1, 2, 3, NAN, NAN, NAN, -1, -2, -3};
  write_text(dir / "a.pcd", pcd_header("ascii", 4) + "0 0 0\n1 2 3\nnan nan nan\n-1 -2 -3\n");
  write_text(dir / "b.pcd", pcd_header("binary", 4) +
                                std::string(reinterpret_cast<const char*>(xyz.data()), xyz.size() * 4));
  std::string planar;  // binary_compressed stores each field's values together
  for (int field = 0; field < 3; ++field)
    for (int point = 0; point < 4; ++point)
      planar.append(reinterpret_cast<const char*>(&xyz[point * 3 + field]), 4);
  const std::string compressed = lzf_literals(planar);
  std::uint32_t sizes[2] = {static_cast<std::uint32_t>(compressed.size()),
                            static_cast<std::uint32_t>(planar.size())};
  write_text(dir / "c.pcd", pcd_header("binary_compressed", 4) +
                                std::string(reinterpret_cast<char*>(sizes), 8) + compressed);
  for (const char* name : {"a.pcd", "b.pcd", "c.pcd"}) {
    const CloudFile read = read_cloud_file(dir / name);
    ASSERT_EQ(read.cloud.points.rows(), 3) << name;
    EXPECT_EQ(read.dropped_non_finite, 1u) << name;
    EXPECT_DOUBLE_EQ(read.cloud.points(2, 1), -2.0) << name;
  }
}

TEST(CloudIo, BadFilesFailWithTheFileNamed) {
  testing::TempDir dir;
  write_text(dir / "empty.ply", "");
  write_text(dir / "nan.xyz", "nan nan nan\nnan 1 2\n");
  write_text(dir / "cloud.abc", "0 0 0\n");
  write_text(dir / "broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  for (const char* name : {"missing.ply", "empty.ply", "nan.xyz", "cloud.abc", "broken.ply"}) {
    try {
      read_cloud_file(dir / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
    }
  }
}

TEST(AtomicFile, LeavesNothingBehindWhenTheWriterFails) {
  testing::TempDir dir;
  EXPECT_THROW(write_atomically(dir / "out.ply",
                                [](const std::filesystem::path& temporary) {
                                  std::ofstream(temporary) << "half";
                                  throw InputError("disk full");
                                }),
               InputError);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace partreg::io
