// Files a library would have trusted: PCDs read by partreg's own reader, glTF/GLB and .vtp checked before
// assimp or VTK parse them, files an input names (buffers, materials) and side files (labels, frames) held
// to the input checks, FIFO outputs that nobody reads, outputs that collide, dataset names that cannot be
// written back. Each refusal is an InputError (or UsageError) naming the file, quickly.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <vector>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/output_format.hpp"
#include "support/temp_dir.hpp"

#include "../support/refusals.hpp"

namespace partreg::io {
namespace {

class Untrusted : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    std::filesystem::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  }
  std::filesystem::path fifo(const std::string& name) const {
    EXPECT_EQ(::mkfifo((dir / name).c_str(), 0600), 0);
    return dir / name;
  }
  static void expect_refused(const std::function<void()>& read, const std::string& name, const std::string& words) {
    testing::expect_refused(read, name, words);
  }
};

const std::string kPcdHeader =
    "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n";

TEST_F(Untrusted, RaggedAsciiPcdRowsAreRefusedNotPadded) {
  // PCL read "0 0" then "1 0 0 5 5" as two points at the origin.
  expect_refused([&] { read_cloud_file(write("ragged.pcd", kPcdHeader + "DATA ascii\n0 0\n1 0 0 5 5\n")); },
                 "ragged.pcd", "data line 1 has fewer values");
  expect_refused([&] { read_cloud_file(write("long.pcd", kPcdHeader + "DATA ascii\n0 0 0 7\n1 0 0\n")); },
                 "long.pcd", "data line 1 has more values");
  expect_refused(
      [&] { read_cloud_file(write("extra.pcd", kPcdHeader + "DATA ascii\n0 0 0\n1 0 0\n2 0 0\n")); },
      "extra.pcd", "more points than the header declares");
  expect_refused([&] { read_cloud_file(write("word.pcd", kPcdHeader + "DATA ascii\n0 0 0\n1 zero 0\n")); },
                 "word.pcd", "'zero' is not a number");
  expect_refused([&] { read_cloud_file(write("short.pcd", kPcdHeader + "DATA ascii\n0 0 0\n")); },
                 "short.pcd", "truncated");
}

// A PLY value that is no number was reported as the end of the file; nan and inf read as in every format
// (those points are dropped).
TEST_F(Untrusted, PlyValuesThatAreNoNumberAreNamedNotCalledTruncated) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const CloudFile cloud = read_cloud_file(write("nan.ply", header + "0 0 0\nnan 1 2\n1 1 1\n"));
  EXPECT_EQ(cloud.cloud.points.rows(), 2);
  EXPECT_EQ(cloud.dropped_non_finite, 1u);
  expect_refused([&] { read_cloud_file(write("word.ply", header + "0 0 0\nx1 1 2\n1 1 1\n")); }, "word.ply",
                 "PLY value 'x1' is not a number");
  expect_refused([&] { read_cloud_file(write("cut.ply", header + "0 0 0\n1 1 2\n1 1\n")); }, "cut.ply",
                 "truncated");
}

// Fields of every type, a padding field of three values and a packed colour, in ASCII and binary: the
// reader puts each value where its header says.
TEST_F(Untrusted, PcdFieldsOfEveryTypeAreReadWhereTheHeaderPutsThem) {
  const std::string header =
      "FIELDS x y z _ label intensity rgb\nSIZE 4 8 4 1 2 4 4\nTYPE F F F U I F U\nCOUNT 1 1 1 3 1 1 1\n"
      "WIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  write("a.pcd", header + "DATA ascii\n1 2 3 0 0 0 -7 0.5 16711935\n4 5 6 9 9 9 300 1.5 65280\n");
  std::string binary = header + "DATA binary\n";
  auto put = [&binary](auto value) { binary.append(reinterpret_cast<const char*>(&value), sizeof value); };
  put(1.0f), put(2.0), put(3.0f), binary += std::string(3, '\0'), put(std::int16_t{-7}), put(0.5f),
      put(16711935u);
  put(4.0f), put(5.0), put(6.0f), binary += std::string(3, '\x09'), put(std::int16_t{300}), put(1.5f),
      put(65280u);
  write("b.pcd", binary);
  for (const char* name : {"a.pcd", "b.pcd"}) {
    const CloudFile cloud = read_cloud_file(dir / name);
    ASSERT_EQ(cloud.cloud.points.rows(), 2) << name;
    EXPECT_EQ(cloud.cloud.points(1, 1), 5.0) << name;
    EXPECT_EQ(cloud.cloud.points(0, 2), 3.0) << name;
    EXPECT_EQ(cloud.attributes.integers.at("label")[0], -7) << name;
    EXPECT_EQ(cloud.attributes.integers.at("label")[1], 300) << name;
    EXPECT_EQ(cloud.attributes.reals.at("intensity")[1], 1.5) << name;
    EXPECT_EQ(cloud.attributes.integers.at("red")[0], 255) << name;
    EXPECT_EQ(cloud.attributes.integers.at("blue")[0], 255) << name;
    EXPECT_EQ(cloud.attributes.integers.at("green")[1], 255) << name;
    EXPECT_EQ(cloud.attributes.integers.at("red")[1], 0) << name;
    EXPECT_EQ(cloud.attributes.integers.count("_"), 0u) << name;
  }
  expect_refused(
      [&] {
        read_cloud_file(write("wide.pcd", header + "DATA ascii\n1 2 3 0 0 0 40000 0 0\n"
                                                   "1 2 3 0 0 0 1 0 0\n"));
      },
      "wide.pcd", "'40000' does not fit field 'label'");
}

// binary_compressed: LZF with a back reference (four literal bytes, then eight copied from four back).
TEST_F(Untrusted, CompressedPcdBackReferencesAreDecodedAndCheckedAgainstBothBuffers) {
  const std::string header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA "
      "binary_compressed\n";
  const float one = 1.0f;
  std::string lzf(1, '\x03');
  lzf.append(reinterpret_cast<const char*>(&one), 4);
  lzf += std::string("\xc0\x03", 2);  // length 6 + 2 = 8, back 3 + 1 = 4
  auto file = [&](const std::string& stream, std::uint32_t unpacked) {
    const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(stream.size()), unpacked};
    return header + std::string(reinterpret_cast<const char*>(sizes), 8) + stream;
  };
  const CloudFile cloud = read_cloud_file(write("c.pcd", file(lzf, 12)));
  ASSERT_EQ(cloud.cloud.points.rows(), 1);
  EXPECT_EQ(cloud.cloud.points.row(0), Eigen::RowVector3d(1, 1, 1));
  std::string far = lzf;
  far[6] = '\x10';  // back 17: before the start of the output
  expect_refused([&] { read_cloud_file(write("far.pcd", file(far, 12))); }, "far.pcd",
                 "compressed data is corrupt");
  expect_refused([&] { read_cloud_file(write("cut.pcd", file(lzf.substr(0, 5), 12))); }, "cut.pcd",
                 "corrupt");
}

// A triangle as glTF: `buffer` is the buffer's uri ("" for none: a GLB's own chunk).
std::string gltf_json(const std::string& buffer, const std::string& nodes = R"([{"mesh":0}])") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":36)" +
         (buffer.empty() ? "" : R"(,"uri":")" + buffer + "\"") +
         R"(}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,)"
         R"("count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]})";
}

std::string triangle_bytes() {
  const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(corners), sizeof corners);
}

std::string glb(std::string json, std::uint32_t stated_length = 0) {
  json.append((4 - json.size() % 4) % 4, ' ');
  const std::string bin = triangle_bytes();
  std::string out = "glTF";
  auto put = [&out](std::uint32_t value) { out.append(reinterpret_cast<const char*>(&value), 4); };
  put(2),
      put(stated_length ? stated_length : static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put(static_cast<std::uint32_t>(json.size())), out += "JSON", out += json;
  put(static_cast<std::uint32_t>(bin.size())), out += std::string("BIN\0", 4), out += bin;
  return out;
}

TEST_F(Untrusted, GltfAndGlbFilesAreReadWithTheirBuffersBesideThem) {
  write("model/triangle.bin", triangle_bytes());
  EXPECT_EQ(read_mesh(write("model/a.gltf", gltf_json("triangle.bin"))).faces.rows(), 1);
  EXPECT_EQ(read_mesh(write("b.glb", glb(gltf_json("")))).faces.rows(), 1);
  write("model/sub/triangle.bin", triangle_bytes());
  EXPECT_EQ(read_mesh(write("model/c.gltf", gltf_json("sub/../sub/triangle.bin"))).faces.rows(), 1);
}

TEST_F(Untrusted, GltfFilesThatCrashedOrHungAssimpAreRefusedFirst) {
  const auto start = std::chrono::steady_clock::now();
  expect_refused([&] { read_mesh(write("deep.gltf", std::string(200000, '[') + std::string(200000, ']'))); },
                 "deep.gltf", "nests deeper than 100 levels");
  std::string chain = "[";
  for (int i = 0; i < 30000; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
  chain += "{}]";
  expect_refused([&] { read_mesh(write("chain.gltf", gltf_json("", chain))); }, "chain.gltf",
                 "deeper than 256 levels");
  expect_refused(
      [&] { read_mesh(write("cycle.gltf", gltf_json("", R"([{"children":[1]},{"children":[0]}])"))); },
      "cycle.gltf", "has a cycle");
  expect_refused(
      [&] { read_mesh(write("twice.gltf", gltf_json("", R"([{"children":[2]},{"children":[2]},{}])"))); },
      "twice.gltf", "has two parents");
  expect_refused([&] { read_mesh(write("chunk.glb", glb(gltf_json(""), 0xFFFFFFF0u))); }, "chunk.glb",
                 "its GLB header states 4294967280 bytes");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

TEST_F(Untrusted, FilesAGltfOrObjNamesMustBeRegularFilesInsideItsFolder) {
  write("secret.bin", triangle_bytes());
  expect_refused([&] { read_mesh(write("model/up.gltf", gltf_json("../secret.bin"))); }, "up.gltf",
                 "outside its own folder");
  expect_refused([&] { read_mesh(write("model/abs.gltf", gltf_json((dir / "secret.bin").string()))); },
                 "abs.gltf", "secret.bin");
  fifo("model/pipe.bin");
  expect_refused([&] { read_mesh(write("model/pipe.gltf", gltf_json("pipe.bin"))); }, "pipe.gltf",
                 "not a regular file");
  // An OBJ's material library that is a FIFO is not opened (it blocked forever): the geometry still reads.
  fifo("pipe.mtl");
  const core::Mesh mesh = read_mesh(write("m.obj", "mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(mesh.faces.rows(), 1);
}

const std::string kVtp =
    R"(<?xml version="1.0"?><VTKFile type="PolyData" version="0.1" byte_order="LittleEndian"><PolyData>)"
    R"(<Piece NumberOfPoints="3" NumberOfPolys="1"><Points><DataArray type="Float32" NumberOfComponents="3" )"
    R"(format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points><Polys><DataArray type="Int32" Name="connectivity" )"
    R"(format="ascii">0 1 2</DataArray><DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>)"
    R"(</Polys></Piece></PolyData></VTKFile>)";

TEST_F(Untrusted, VtpNestingAndDeclaredCountsAreCheckedBeforeVtk) {
  EXPECT_EQ(read_mesh(write("ok.vtp", kVtp)).faces.rows(), 1);
  std::string deep = R"(<?xml version="1.0"?><VTKFile type="PolyData">)";
  for (int i = 0; i < 200000; ++i) deep += "<a>";
  expect_refused([&] { read_cloud_file(write("deep.vtp", deep)); }, "deep.vtp", "XML nests deeper than 100");
  std::string huge = kVtp;
  huge.replace(huge.find("NumberOfPoints=\"3\""), 18, "NumberOfPoints=\"99999999999\"");
  expect_refused([&] { read_cloud_file(write("huge.vtp", huge)); }, "huge.vtp",
                 "declares 99999999999 NumberOfPoints");
}

TEST_F(Untrusted, SideFilesMustBeRegularFiles) {
  // A FIFO as a labels or frames file blocked forever.
  fifo("labels.json");
  fifo("frames.json");
  expect_refused([&] { read_labels_file(dir / "labels.json"); }, "labels.json", "not a regular file");
  expect_refused([&] { read_frames_file(dir / "frames.json"); }, "frames.json", "not a regular file");
}

TEST_F(Untrusted, AFifoOutputThatNobodyReadsFailsInsteadOfBlocking) {
  const auto target = fifo("out.xyz");
  core::Cloud cloud;
  cloud.points = core::Points::Zero(3, 3);
  const auto start = std::chrono::steady_clock::now();
  expect_refused([&] { write_cloud(target, cloud, {}); }, "out.xyz", "no process read the FIFO");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(kFifoReaderWaitSeconds + 5));
}

TEST_F(Untrusted, OutputsOfOneCommandMustBeDistinct) {
  EXPECT_NO_THROW(check_distinct_outputs({{"--out", "a.ply"}, {"--json", "a.json"}, {"--frames-out", ""}}));
  EXPECT_NO_THROW(check_distinct_outputs({{"--out", "/dev/null"}, {"--json", "/dev/null"}}));
  auto expect_clash = [](const std::vector<NamedOutput>& outputs, const std::string& words) {
    try {
      check_distinct_outputs(outputs);
      ADD_FAILURE() << words << ": accepted";
    } catch (const UsageError& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  const std::string same = (dir / "same.ply").string();
  expect_clash({{"--points-out", same}, {"--mesh-out", same}},
               "--points-out and --mesh-out name the same output");
  expect_clash({{"--out", "-"}, {"--json", "/dev/stdout"}}, "--out and --json");
  std::filesystem::create_symlink(same, dir / "link.ply");
  expect_clash({{"--points-out", same}, {"--mesh-out", (dir / "." / "link.ply").string()}},
               "same output");
}

TEST_F(Untrusted, DatasetNamesThatCannotBeWrittenBackAreRefused) {
  const std::string cube = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
  for (const std::string bad : std::vector<std::string>{"mug\nb.obj", "mug,b.obj", "mug\xff.obj"}) {
    testing::TempDir set;
    std::ofstream(set / "mug_a.obj") << cube;
    std::ofstream(set / bad) << cube;
    DatasetOptions options;
    options.points_per_instance = 50;
    expect_refused([&] { read_dataset(set.path(), options); }, "dataset entry", "rename it");
  }
}

}  // namespace
}  // namespace partreg::io
