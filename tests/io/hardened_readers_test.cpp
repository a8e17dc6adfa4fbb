// Every reader checks before it trusts. Each case is a file that would crash, hang or exhaust
// memory in a careless reader: it must be refused with an InputError naming the file, quickly.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>

#include "partreg/core/errors.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "support/temp_dir.hpp"

#include "../support/refusals.hpp"

namespace partreg::io {
namespace {

class Hardened : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  }
  static void expect_refused(const std::function<void()>& read, const std::string& name, const std::string& words) {
    testing::expect_refused(read, name, words);
  }
  void expect_cloud_refused(const std::string& name, const std::string& bytes, const std::string& words) {
    const auto path = write(name, bytes);
    expect_refused([&] { read_cloud_file(path); }, name, words);
  }
  void expect_mesh_refused(const std::string& name, const std::string& bytes, const std::string& words) {
    const auto path = write(name, bytes);
    expect_refused([&] { read_mesh(path); }, name, words);
  }
};

const std::string kPcdFields =
    "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n";

TEST_F(Hardened, MalformedPcdFilesAreRefusedBeforePclSeesThem) {
  // PCL crashed on each of these (exit 139).
  expect_cloud_refused("text.pcd", "0.1 0.2 0.3\n", "not a PCD file");
  expect_cloud_refused("no_data.pcd", kPcdFields + "POINTS 3\n", "no DATA line");
  expect_cloud_refused("fields.pcd", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n0 0 0\n",
                       "SIZE lists 2 values for 3 fields");
  expect_cloud_refused("noz.pcd", "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n0 0\n",
                       "no 'z' field");
  expect_cloud_refused("short.pcd", kPcdFields + "POINTS 3\nDATA binary\n" + std::string(20, '\0'),
                       "declares 3 points");
  expect_cloud_refused("huge.pcd", kPcdFields + "POINTS 3000000000\nDATA binary\n", "more than partreg reads");
  expect_cloud_refused("points.pcd", kPcdFields + "POINTS 4\nDATA ascii\n0 0 0\n0 0 0\n0 0 0\n", "not POINTS");
  std::string compressed = kPcdFields + "POINTS 3\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {1000, 36};
  compressed.append(reinterpret_cast<const char*>(sizes), sizeof sizes);
  expect_cloud_refused("lzf.pcd", compressed + "abc", "compressed data claims 1000 bytes");
  // Found by fuzz_pcd: PCL takes an unknown line for the start of the data and crashes reading it.
  expect_cloud_refused("unknown_line.pcd", "VERSIO N 0.7\n" + kPcdFields + "POINTS 3\nDATA ascii\n0 0 0\n0 0 0\n0 0 0\n",
                       "unknown PCD header line 'VERSIO'");
  expect_cloud_refused("control.pcd", "VERSIO\x1aN 0.7\n" + kPcdFields + "POINTS 3\nDATA ascii\n0 0 0\n0 0 0\n0 0 0\n",
                       "control character");
  expect_cloud_refused("double_size.pcd", "FIELDS x y z\nSIZE 2 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n0 0 0\n",
                       "floating point of size 2");
}

// The face-list check walks every row in the file's byte order: quads and big-endian files still read.
TEST_F(Hardened, BinaryPlyMeshesWithPolygonsAndBothByteOrdersAreRead) {
  for (const bool big : {false, true}) {
    std::string bytes = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list ushort int vertex_indices\nend_header\n";
    auto put = [&](const void* value, std::size_t size) {
      std::string raw(static_cast<const char*>(value), size);
      if (big) std::reverse(raw.begin(), raw.end());
      bytes += raw;
    };
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& corner : corners)
      for (const float c : corner) put(&c, sizeof c);
    const std::uint16_t count = 4;
    put(&count, sizeof count);
    for (const std::int32_t index : {0, 1, 2, 3}) put(&index, sizeof index);
    const core::Mesh mesh = read_mesh(write(big ? "big.ply" : "little.ply", bytes));
    EXPECT_EQ(mesh.vertices.rows(), 4);
    EXPECT_EQ(mesh.faces.rows(), 2) << "the quad is split into two triangles";
    EXPECT_FLOAT_EQ(mesh.vertices.col(0).maxCoeff(), 1.0f);
  }
}

TEST_F(Hardened, PlyCountsAreCheckedAgainstTheFileSizeAndTheBudget) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex ";
  const std::string properties = "\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
  // 10^9 vertices allocated 24 GB and was killed; 10^8 read for a minute before saying "truncated".
  expect_cloud_refused("billion.ply", header + "1000000000" + properties, "more than partreg reads");
  expect_cloud_refused("hundred_million.ply", header + "100000000" + properties, "more than partreg reads");
  expect_cloud_refused("ten_million.ply", header + "10000000" + properties, "truncated");
  expect_cloud_refused("binary.ply",
                       "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                       "property float z\nend_header\n" + std::string(40, '\0'),
                       "declares 5 vertices");
  expect_cloud_refused("negative.ply", header + "-3" + properties, "malformed PLY element");
  expect_cloud_refused("no_end.ply", header + "1\nproperty float x\n" + std::string(100, 'a'), "end_header");
  expect_cloud_refused("endless_header.ply", "ply\n" + std::string(3 << 20, 'x'), "header is longer");
}

const std::string kTriangleHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\n";

TEST_F(Hardened, MeshFilesThatCrashedAssimpAreRefused) {
  // A header without end_header made `label` loop forever inside assimp.
  expect_mesh_refused("no_end.ply", kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "end_header missing");
  expect_mesh_refused("no_end_at_all.ply", kTriangleHeader, "no end_header");
  // A face naming a vertex that does not exist crashed label, views and render.
  expect_mesh_refused("index.ply", kTriangleHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "out of range");
  // A truncated binary mesh crashed in assimp's post-processing.
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 300\nproperty float x\nproperty float y\n"
      "property float z\nelement face 100\nproperty list uchar int vertex_indices\nend_header\n";
  binary += std::string(1000, '\0');
  expect_mesh_refused("truncated.ply", binary, "truncated");
  // Found by fuzz_mesh: assimp aborts on a header line the PLY grammar does not have.
  expect_mesh_refused("unknown_line.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\npropert\x01\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
                      "unknown PLY header line");
  expect_mesh_refused("no_y.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
                      "no 'y' property");
  // Found by fuzz_mesh in CI: assimp's triangulation aborts on a face of 0 vertices, binary or text.
  std::string empty_face =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  empty_face += std::string(36, '\0') + std::string(1, '\0') + std::string(8, '\1');
  expect_mesh_refused("empty_face.ply", empty_face, "PLY face 0 lists 0 vertices");
  expect_mesh_refused("line_face.ply", kTriangleHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                      "PLY face 0 lists 2 vertices");
  expect_mesh_refused("negative_list.ply", kTriangleHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n",
                      "has a list of -3 values");
  // An OFF file claiming more faces than it holds aborted.
  expect_mesh_refused("faces.off", "OFF\n3 1000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "declares 1000 faces");
  expect_mesh_refused("few_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" + std::string(40, '\n'),
                      "ends after 1 of its 2 faces");
  expect_mesh_refused("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "not one of the 3 vertices");
  expect_mesh_refused("negative.off", "OFF\n-3 1 0\n0 0 0\n", "non-negative");
}

TEST_F(Hardened, OffMeshesStillReadWithPolygonsFanned) {
  const core::Mesh mesh =
      read_mesh(write("quad.off", "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"));
  EXPECT_EQ(mesh.vertices.rows(), 4);
  EXPECT_EQ(mesh.faces.rows(), 2);
}

TEST_F(Hardened, XyzColoursAreKeptNotReadAsNormals) {
  CloudFile colours = read_cloud_file(write("rgb.xyz", "0 0 0 255 0 0\n1 0 0 0 128 0\n0 1 0 0 0 255\n"));
  EXPECT_EQ(colours.cloud.normals.rows(), 0);
  ASSERT_TRUE(colours.attributes.integers.count("red"));
  EXPECT_EQ(colours.attributes.integers["red"][0], 255);
  EXPECT_EQ(colours.attributes.integers["green"][1], 128);
  CloudFile normals = read_cloud_file(write("n.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n0 1 0 0 0.6 0.8\n"));
  EXPECT_EQ(normals.cloud.normals.rows(), 3);
  EXPECT_TRUE(normals.attributes.integers.empty());
}

TEST_F(Hardened, LabelColoursAndFramePositionsAreRangeChecked) {
  const auto labels = write("l.json",
                            R"({"format":"partreg-labels","version":1,"source":"m.obj","target":"faces",)"
                            R"("parts":[{"name":"a","color":[300,0,0]}],"count":1,"labels":[0]})");
  expect_refused([&] { read_labels_file(labels); }, "l.json", "outside 0..255");
  const auto frames = write("f.json",
                            R"({"format":"partreg-frames","version":1,"frames":[{"name":"g","position":[1e308,0,0],)"
                            R"("rotation":[[1,0,0],[0,1,0],[0,0,1]]}]})");
  expect_refused([&] { read_frames_file(frames); }, "f.json", "position of frame 'g'");
  const auto not_object = write("array.json", "[1,2,3]");
  expect_refused([&] { read_frames_file(not_object); }, "array.json", "not a partreg frames file");
  expect_refused([&] { read_labels_file(not_object); }, "array.json", "not a partreg labels file");
}

// --- model files ---

core::CategoryModel small_model() {
  std::vector<core::TrainingInstance> instances;
  for (const auto& synthetic : core::make_synthetic_category(core::SyntheticCategory::mug, 3, 3)) {
    core::TrainingInstance instance;
    instance.name = synthetic.name;
    const auto samples = core::sample_correspondences(core::SyntheticCategory::mug, synthetic.shape_parameters, 300, 5);
    instance.points = samples.points;
    instance.part = samples.part;
    instances.push_back(instance);
  }
  core::TrainingSettings settings;
  settings.canonical_points = 80;
  settings.target_points = 150;
  return core::train_category("mugs", instances, {"body", "handle"}, settings);
}

std::uint64_t fnv1a64(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ULL;
  return hash;
}

// Edits the JSON header of a model file's bytes as a crafted file would, keeping its length field and its
// header checksum right, so the edit reaches the checks behind them.
std::string with_header_edit(const std::string& bytes, const std::string& from, const std::string& to) {
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + 8, 8);
  const std::string arrays = bytes.substr(16 + length);
  std::string header = bytes.substr(16, length);
  const auto at = header.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the header");
  header.replace(at, from.size(), to);
  const std::string key = "\"header_fnv1a64\":\"";
  const auto digits = header.find(key) + key.size();
  header.replace(digits, 16, std::string(16, '0'));
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(header)));
  header.replace(digits, 16, hex);
  length = header.size();
  return bytes.substr(0, 8) + std::string(reinterpret_cast<const char*>(&length), 8) + header + arrays;
}

TEST_F(Hardened, ModelFileBoundsCannotWrapAndItsHeaderIsChecksummed) {
  write_model(dir / "m.prm", small_model());
  std::ifstream in(dir / "m.prm", std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  ASSERT_NO_THROW(read_model(dir / "m.prm"));
  // A negative offset passed `offset + bytes > size` by wrap-around and read before the buffer.
  const std::string first_array = "\"offset\":0,";
  write("negative.prm", with_header_edit(bytes, first_array, "\"offset\":-8,"));
  expect_refused([&] { read_model(dir / "negative.prm"); }, "negative.prm", "negative or non-integer");
  write("wrapping.prm", with_header_edit(bytes, first_array, "\"offset\":18446744073709551608,"));
  expect_refused([&] { read_model(dir / "wrapping.prm"); }, "wrapping.prm", "runs past the end");
  // One flipped bit in the normalisation scale loaded silently.
  std::string flipped = bytes;
  const auto scale = flipped.find_first_of("0123456789", flipped.find("\"scale\":") + 10);
  flipped[scale] ^= 0x01;  // a digit stays a digit: the JSON still parses
  write("flipped.prm", flipped);
  expect_refused([&] { read_model(dir / "flipped.prm"); }, "flipped.prm", "checksum of its header");
  // A flipped bit in the checksum's own name is damage too, not an old file without a checksum.
  std::string renamed = bytes;
  renamed[renamed.find("header_fnv1a64") + 1] ^= 0x02;
  write("renamed.prm", renamed);
  expect_refused([&] { read_model(dir / "renamed.prm"); }, "renamed.prm", "unknown header member");
}

TEST_F(Hardened, ValidateChecksEveryValuesRange) {
  const core::CategoryModel good = small_model();
  ASSERT_NO_THROW(good.validate());
  auto expect_invalid = [](const core::CategoryModel& model, const std::string& words) {
    try {
      model.validate();
      ADD_FAILURE() << "accepted: " << words;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  core::CategoryModel zero_scale = good;
  zero_scale.normalization.scale = 0.0;
  expect_invalid(zero_scale, "normalisation scale");
  core::CategoryModel nan_basis = good;
  nan_basis.spaces[1].basis(0, 0) = std::nan("");
  expect_invalid(nan_basis, "NaN");
  core::CategoryModel bad_part = good;
  bad_part.canonical_part[0] = 7;
  expect_invalid(bad_part, "part index out of range");
  core::CategoryModel negative_variance = good;
  negative_variance.spaces[0].variances[0] = -1.0;
  expect_invalid(negative_variance, "variance is negative");
  // write_model refuses what validate refuses: nothing invalid reaches a file.
  EXPECT_THROW(write_model(dir / "zero.prm", zero_scale), InputError);
}

}  // namespace
}  // namespace partreg::io
