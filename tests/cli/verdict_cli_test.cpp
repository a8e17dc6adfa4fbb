// `partreg register`'s verdict on the command line: its last stderr line, `--fail-on` and exit 3, and a model
// with a real size (`train --size`) taking clouds in metres and refusing millimetres.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

using testing::Outcome;

class VerdictCli : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::string path(const std::string& name) const { return (dir / name).string(); }
  Outcome run(const std::string& arguments) const { return testing::run_partreg(arguments); }

  // A synthetic mug category, a model of it, and a mug-shaped cloud (.xyz) to register.
  void SetUp() override {
    ASSERT_EQ(run("synth mug --out " + path("mugs") + " --instances 4 --seed 3").exit_code, 0);
    ASSERT_EQ(run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300").exit_code, 0);
    const Outcome sampled = run("register " + path("mug.prm") + " " + path("mugs/ground_truth/mug_003.ply") +
                                " --points-out " + path("mug.xyz"));
    ASSERT_EQ(sampled.exit_code, 0) << sampled.output;
  }

  // The positions of an .xyz file (each line x y z, then its normal where written).
  std::vector<Eigen::Vector3d> positions_of(const std::string& name) const {
    std::ifstream in(dir / name);
    std::vector<Eigen::Vector3d> positions;
    for (std::string line; std::getline(in, line);) {
      std::istringstream fields(line);
      Eigen::Vector3d p;
      if (fields >> p.x() >> p.y() >> p.z()) positions.push_back(p);
    }
    return positions;
  }

  // The positions of mug.xyz, each multiplied by `factor`, with `extra` rows after them.
  void write_scaled(const std::string& name, double factor, const std::string& extra = "") const {
    std::ofstream out(dir / name);
    for (const Eigen::Vector3d& p : positions_of("mug.xyz"))
      out << p.x() * factor << ' ' << p.y() * factor << ' ' << p.z() * factor << '\n';
    out << extra;
  }

  // The bounding box of an .xyz file: lowest and highest coordinates.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounds_of(const std::string& name) const {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
    for (const Eigen::Vector3d& p : positions_of(name)) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    return {low, high};
  }
  double diagonal_of(const std::string& name) const {
    const auto [low, high] = bounds_of(name);
    return (high - low).norm();
  }

  static std::string last_line(const std::string& output) {
    std::istringstream lines(output);
    std::string line, last;
    while (std::getline(lines, line))
      if (!line.empty()) last = line;
    return last;
  }
};

TEST_F(VerdictCli, AGoodRegistrationEndsOnItsVerdictAndPassesFailOn) {
  const Outcome good = run("register " + path("mug.prm") + " " + path("mug.xyz") + " --fail-on doubtful --json " +
                           path("r.json"));
  ASSERT_EQ(good.exit_code, 0) << good.output;
  EXPECT_EQ(last_line(good.output).rfind("verdict: good", 0), 0u) << good.output;
  const nlohmann::json result = nlohmann::json::parse(std::ifstream(dir / "r.json"));
  EXPECT_EQ(result.at("assessment").at("verdict"), "good");
  EXPECT_GT(result.at("assessment").at("figures").at("inlier_share").get<double>(), 0.9);
}

TEST_F(VerdictCli, ATablePlaneLeftInExitsThreeUnderFailOnAndZeroWithout) {
  // A table twice the mug's diagonal wide under its base (the synthetic mugs stand on y): most points are
  // not the mug.
  const auto [low, high] = bounds_of("mug.xyz");
  const Eigen::Vector3d centre = 0.5 * (low + high);
  const double half = (high - low).norm();
  std::ostringstream plane;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      plane << centre.x() - half + half * i / 20.0 << ' ' << low.y() << ' ' << centre.z() - half + half * j / 20.0
            << '\n';
  write_scaled("scene.xyz", 1.0, plane.str());
  const std::string register_scene = "register " + path("mug.prm") + " " + path("scene.xyz");
  const Outcome plain = run(register_scene);
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("verdict: failed"), std::string::npos) << plain.output;
  const Outcome rejected = run(register_scene + " --fail-on failed --json " + path("scene.json"));
  EXPECT_EQ(rejected.exit_code, 3) << rejected.output;
  EXPECT_NE(last_line(rejected.output).find("partreg: the verdict is failed"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "scene.json"));  // the outputs are written first
  EXPECT_EQ(run(register_scene + " --fail-on doubtful").exit_code, 3);
  EXPECT_EQ(run(register_scene + " --fail-on sometimes").exit_code, 2);
}

TEST_F(VerdictCli, AModelWithARealSizeRegistersMetresAndRefusesMillimetres) {
  ASSERT_EQ(run("train " + path("mugs") + " --out " + path("metric.prm") + " --points 300 --size 0.12").exit_code, 0);
  // The mug brought to 12 cm across its diagonal.
  const double to_metres = 0.12 / diagonal_of("mug.xyz");
  write_scaled("metres.xyz", to_metres);
  const Outcome metres = run("register " + path("metric.prm") + " " + path("metres.xyz"));
  ASSERT_EQ(metres.exit_code, 0) << metres.output;
  EXPECT_EQ(last_line(metres.output).rfind("verdict: good", 0), 0u) << metres.output;
  write_scaled("millimetres.xyz", 1000.0 * to_metres);
  const Outcome millimetres = run("register " + path("metric.prm") + " " + path("millimetres.xyz"));
  EXPECT_EQ(millimetres.exit_code, 1) << millimetres.output;
  EXPECT_NE(millimetres.output.find("metres"), std::string::npos) << millimetres.output;
  EXPECT_EQ(run("train " + path("mugs") + " --out " + path("bad.prm") + " --size -1").exit_code, 2);
}

}  // namespace
}  // namespace partreg
