// `partreg scene`, `partreg segment` and `register --depth` through the real executable: a rendered scene is
// cut where its truth says, and every bad input is one line with exit 1 (bad data) or 2 (a bad request),
// leaving no output behind.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"
#include "support/test_shapes.hpp"

namespace partreg {
namespace {

using testing::Outcome;
using testing::run_partreg;
using testing::TempDir;

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The error's one line: the output ends with it, and nothing else reads as an error.
bool one_error_line(const std::string& output) {
  const std::size_t at = output.find("partreg: ");
  return at != std::string::npos && output.find("partreg: ", at + 1) == std::string::npos &&
         output.find('\n', at) == output.size() - 1;
}

// Three balls on a table, rendered once for the whole suite.
class SceneCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    io::write_mesh(*dir_ / "ball.obj", testing::uv_sphere(1.0, 16, 24));
    const std::string ball = (*dir_ / "ball.obj").string();
    const Outcome rendered = run_partreg("scene " + ball + " " + ball + " " + ball + " --size 0.12 --out " +
                                         (*dir_ / "scene").string());
    ASSERT_EQ(rendered.exit_code, 0) << rendered.output;
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string scene(const std::string& name) { return (*dir_ / "scene" / name).string(); }
  static std::string depth_args() {
    return "--depth " + scene("depth.png") + " --intrinsics " + scene("intrinsics.json");
  }
  static TempDir* dir_;
};
TempDir* SceneCommand::dir_ = nullptr;

TEST_F(SceneCommand, RenderedSceneHasItsTruthAndSegmentCutsTheMiddleObject) {
  const nlohmann::json truth = read_json(scene("scene.json"));
  ASSERT_EQ(truth["objects"].size(), 3u);
  for (const auto& object : truth["objects"]) EXPECT_GT(object["measured_pixels"].get<int>(), 1000);
  TempDir out;
  const Outcome cut = run_partreg("segment " + depth_args() + " --out " + (out / "cut").string());
  ASSERT_EQ(cut.exit_code, 0) << cut.output;
  EXPECT_NE(cut.output.find("nearest the image centre"), std::string::npos) << cut.output;
  const nlohmann::json report = read_json(out / "cut" / "segment.json");
  EXPECT_EQ(report["clusters"].size(), 3u);
  // The middle ball's centre in the camera frame: its pose's translation plus its turned, scaled centre (the
  // ball is centred on its own origin, so the translation is its centre).
  const auto& T = truth["objects"][0]["T_camera_object"];
  const Eigen::Vector3d centre(T[0][3].get<double>(), T[1][3].get<double>(), T[2][3].get<double>());
  const core::Points object = io::read_cloud_file(out / "cut" / "object.ply").cloud.points;
  EXPECT_LT((object.colwise().mean().transpose() - centre).norm(), 0.035);
  const auto& plane = report["plane"];
  const auto& table = truth["table_plane"];
  double cosine = 0;
  for (int i = 0; i < 3; ++i) cosine += plane[i].get<double>() * table[i].get<double>();
  EXPECT_GT(cosine, std::cos(M_PI / 180.0));  // within a degree of the true table
}

TEST_F(SceneCommand, BadInputsAreOneLineWithTheirExitCode) {
  TempDir dir;
  std::ofstream(dir / "small.json") << R"({"fx": 615, "fy": 615, "cx": 159.5, "cy": 119.5, "width": 320, "height": 240})";
  std::ofstream(dir / "nan.json") << R"({"fx": NaN, "fy": 615, "cx": 319.5, "cy": 239.5, "width": 640, "height": 480})";
  io::write_cloud(dir / "plane.ply", core::Cloud{testing::fibonacci_sphere(3000, 1.0).array() * Eigen::Array<double, 1, 3>(1, 0, 1).replicate(3000, 1), {}});
  const std::string out = " --out " + (dir / "out").string();
  const std::vector<std::pair<std::string, int>> cases = {
      {"segment --depth " + scene("depth.png") + " --intrinsics " + (dir / "small.json").string() + out, 1},
      {"segment --depth " + scene("depth.png") + " --intrinsics " + (dir / "nan.json").string() + out, 1},
      {"segment --depth " + scene("mask_0.png") + " --intrinsics " + scene("intrinsics.json") + out, 1},
      {"segment " + depth_args() + " --pick 700,10" + out, 2},
      {"segment " + depth_args() + " --pick 1,2,3,4" + out, 2},
      {"segment " + (dir / "plane.ply").string() + out, 1},
      {"segment " + (dir / "plane.ply").string() + " --pick 3,4" + out, 2},
      {"segment --depth " + scene("depth.png") + out, 2},
      {"register nothing.prm " + scene("object_0.ply") + " " + depth_args(), 2},
      {"register nothing.prm " + depth_args() + " --viewpoint 0,0,0", 2},
  };
  for (const auto& [arguments, code] : cases) {
    const Outcome outcome = run_partreg(arguments);
    EXPECT_EQ(outcome.exit_code, code) << arguments << "\n" << outcome.output;
    EXPECT_TRUE(one_error_line(outcome.output)) << arguments << "\n" << outcome.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << arguments;
  }
}

}  // namespace
}  // namespace partreg
