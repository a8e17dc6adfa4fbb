// The real `partreg` executable: exit codes, messages and outputs as a user sees them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/io/model_file.hpp"
#include "support/run_partreg.hpp"
#include "support/shared_data.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

using testing::Outcome;

Outcome run(const std::string& arguments) { return testing::run_partreg(arguments); }

class Cli : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::string path(const std::string& name) const { return (dir / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir / name) << text; }
  std::string cube() const {
    write("cube.obj",
          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
          "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 "
          "5\nf 4 5 8\n");
    return path("cube.obj");
  }
};

TEST_F(Cli, CpdWritesTheMovedPointsAndAJsonReport) {
  const std::string mesh = cube();
  const Outcome result = run("cpd " + mesh + " " + mesh + " --mode rigid --points 300 --out " +
                             path("out.ply") + " --json " + path("r.json"));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out.ply"));
  std::ifstream json(dir / "r.json");
  const std::string text{std::istreambuf_iterator<char>(json), {}};
  EXPECT_NE(text.find("T_target_source"), std::string::npos);
  EXPECT_NE(text.find("sigma2"), std::string::npos);
}

TEST_F(Cli, BadInputGetsOneLineAndTheRightExitCodeAndNoOutput) {
  const std::string mesh = cube();
  write("empty.ply", "");
  write("nan.xyz", "nan nan nan\nnan nan nan\nnan nan nan\n");
  write("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  write("cloud.abc", "0 0 0\n");
  write("few.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  const std::string out = " --out " + path("out.ply");
  const std::vector<std::pair<std::string, int>> cases = {
      {"cpd " + path("missing.ply") + " " + mesh + out, 1},  // a missing input is a runtime failure
      {"cpd " + path("cloud.abc") + " " + mesh + out, 1},
      {"cpd " + path("empty.ply") + " " + mesh + out, 1},
      {"cpd " + path("nan.xyz") + " " + mesh + out, 1},
      {"cpd " + path("flat.obj") + " " + mesh + out, 1},
      {"cpd " + mesh + " " + mesh + " --beta -1" + out, 2},
      {"cpd " + mesh + " " + mesh + " --mode rigid --coarse-points 10" + out, 2},
      {"cpd " + path("nan.xyz") + " " + mesh + " --points 50" + out, 1},
      {"cpd " + path("few.xyz") + " " + mesh + " --points 50" + out, 1},
      {"cpd " + mesh + " " + mesh + " --mode bent" + out, 2},
      {"train " + path("nowhere") + " --out " + path("m.prm"), 1},
      {"info " + path("empty.ply"), 1},
      {"synth teapot --out " + path("synth"), 2},
      {"frobnicate", 2},
  };
  for (const auto& [arguments, code] : cases) {
    const Outcome result = run(arguments);
    EXPECT_EQ(result.exit_code, code) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find("partreg: "), std::string::npos) << arguments << "\n" << result.output;
  }
  for (const std::string& name : dir.entries())
    EXPECT_TRUE(name == "cube.obj" || name == "empty.ply" || name == "nan.xyz" || name == "flat.obj" ||
                name == "cloud.abc" || name == "few.xyz")
        << "left behind: " << name;
}

TEST_F(Cli, SynthTrainInfoMakeAndDescribeAModel) {
  const Outcome synth = run("synth mug --out " + path("mugs") + " --instances 4 --seed 2");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "mugs/mug_000/handle.obj"));
  EXPECT_TRUE(std::filesystem::exists(dir / "mugs/ground_truth/mug_000.ply"));
  const Outcome train = run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 400");
  ASSERT_EQ(train.exit_code, 0) << train.output;
  EXPECT_NE(train.output.find("cpd holistic -> "), std::string::npos);  // one progress line per CPD
  const Outcome info = run("info " + path("mug.prm") + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("\"handle\""), std::string::npos);
  EXPECT_NE(info.output.find("\"explained\""), std::string::npos);
  // The synth output folder is not overwritten.
  EXPECT_EQ(run("synth mug --out " + path("mugs")).exit_code, 2);
}

TEST_F(Cli, TrainRefusesLabelsMadeForAnotherMesh) {
  std::filesystem::create_directories(dir / "cubes");
  for (const char* name : {"a", "b", "c"})
    std::filesystem::copy_file(cube(), dir / "cubes" / (std::string(name) + ".obj"),
                               std::filesystem::copy_options::overwrite_existing);
  write("labels.json",
        R"({"format": "partreg-labels", "version": 1, "source": "a.obj", "parts": [{"name": "body",
      "color": [0, 0, 0]}, {"name": "lid", "color": [1, 1, 1]}], "target": "faces", "count": 3, "labels": [0, 1, 1]})");
  const Outcome train =
      run("train " + path("cubes") + " --labels " + path("labels.json") + " --out " + path("m.prm"));
  EXPECT_EQ(train.exit_code, 1) << train.output;
  EXPECT_NE(train.output.find("12 faces"), std::string::npos) << train.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.prm"));
}

// Labels for two of three cubes: the first file's cube is the canonical, the second trains on its own parts
// (training then measures its label propagation against them); a file listed twice counts once; two files
// for one cube, or files naming different parts, are refused before anything is written.
TEST_F(Cli, TrainTakesSeveralLabelsFilesAndRefusesOnesThatDisagree) {
  std::filesystem::create_directories(dir / "cubes");
  for (const char* name : {"a", "b", "c"})
    std::filesystem::copy_file(cube(), dir / "cubes" / (std::string(name) + ".obj"),
                               std::filesystem::copy_options::overwrite_existing);
  const auto labels = [&](const std::string& file, const std::string& source, const std::string& second) {
    write(file, R"({"format": "partreg-labels", "version": 1, "source": ")" + source +
                    R"(", "parts": [{"name": "body", "color": [0, 0, 0]}, {"name": ")" + second +
                    R"(", "color": [1, 1, 1]}], "target": "faces", "count": 12,
                    "labels": [0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0]})");
    return path(file);
  };
  const std::string a = labels("a.json", "a.obj", "lid"), b = labels("b.json", "b.obj", "lid");
  const Outcome train = run("train " + path("cubes") + " --labels " + a + " --labels " + b + " --labels " +
                            a + " --points 300 --out " + path("m.prm"));
  ASSERT_EQ(train.exit_code, 0) << train.output;
  EXPECT_NE(train.output.find("canonical: a"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("label propagation onto b:"), std::string::npos) << train.output;
  EXPECT_EQ(train.output.find("label propagation onto c:"), std::string::npos) << train.output;

  const Outcome twice = run("train " + path("cubes") + " --labels " + a + " --labels " +
                            labels("a2.json", "a.obj", "lid") + " --out " + path("twice.prm"));
  EXPECT_EQ(twice.exit_code, 2) << twice.output;
  EXPECT_NE(twice.output.find("both label 'a'"), std::string::npos) << twice.output;
  const Outcome other = run("train " + path("cubes") + " --labels " + a + " --labels " +
                            labels("b2.json", "b.obj", "cap") + " --out " + path("other.prm"));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("names other parts"), std::string::npos) << other.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "twice.prm"));
  EXPECT_FALSE(std::filesystem::exists(dir / "other.prm"));

  // Files after one --labels, as a shell glob gives them; --canonical picks another labelled instance, and
  // must name one.
  const Outcome chosen = run("train " + path("cubes") + " --labels " + a + " " + b + " --canonical b" +
                             " --points 300 --out " + path("b.prm"));
  ASSERT_EQ(chosen.exit_code, 0) << chosen.output;
  EXPECT_NE(chosen.output.find("canonical: b"), std::string::npos) << chosen.output;
  EXPECT_NE(chosen.output.find("label propagation onto a:"), std::string::npos) << chosen.output;
  const Outcome unlabelled = run("train " + path("cubes") + " --labels " + a + " " + b + " --canonical c" +
                                 " --out " + path("c.prm"));
  EXPECT_EQ(unlabelled.exit_code, 2) << unlabelled.output;
  EXPECT_NE(unlabelled.output.find("none of the labelled instances"), std::string::npos) << unlabelled.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.prm"));
}

TEST_F(Cli, TrainRefusesPartFoldersThatDisagreeAndWritesNoModel) {
  ASSERT_EQ(run("synth mug --out " + path("mugs") + " --instances 3").exit_code, 0);
  std::filesystem::rename(dir / "mugs/mug_001/handle.obj", dir / "mugs/mug_001/grip.obj");
  const Outcome train = run("train " + path("mugs") + " --out " + path("mug.prm"));
  EXPECT_EQ(train.exit_code, 1) << train.output;
  EXPECT_NE(train.output.find("mug_001"), std::string::npos) << train.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "mug.prm"));
}

// A folder of part meshes as the truth (the synthetic mug's own parts): each part is scored against its own
// as well, in the JSON and on the command line; a model without parts refuses such a truth.
TEST_F(Cli, RegisterScoresEachPartAgainstItsOwnWhenTheTruthHasParts) {
  ASSERT_EQ(run("synth mug --out " + path("mugs") + " --instances 4 --seed 3").exit_code, 0);
  ASSERT_EQ(run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300").exit_code, 0);
  const Outcome good =
      run("register " + path("mug.prm") + " " + path("mugs/ground_truth/mug_003.ply") +
          " --variant coupled --json " + path("r.json") + " --truth " + path("mugs/mug_003"));
  ASSERT_EQ(good.exit_code, 0) << good.output;
  EXPECT_NE(good.output.find("each part against its own: mean "), std::string::npos) << good.output;
  std::ifstream json(dir / "r.json");
  const nlohmann::json truth = nlohmann::json::parse(json).at("truth");
  const nlohmann::json& own = truth.at("own_part_rms_per_diagonal");
  ASSERT_EQ(own.size(), 2u);
  // In place: each part within 5% of the diagonal of its own (body and handle are 20-30% apart).
  for (const char* part : {"body", "handle"}) EXPECT_LT(own.at(part).get<double>(), 0.05) << part;
  EXPECT_NEAR(truth.at("own_part_rms_mean_per_diagonal").get<double>(),
              0.5 * (own.at("body").get<double>() + own.at("handle").get<double>()), 1e-12);

  std::filesystem::create_directories(dir / "cubes");
  for (const char* name : {"a", "b", "c"})
    std::filesystem::copy_file(cube(), dir / "cubes" / (std::string(name) + ".obj"),
                               std::filesystem::copy_options::overwrite_existing);
  ASSERT_EQ(run("train " + path("cubes") + " --points 300 --out " + path("cube.prm")).exit_code, 0);
  const Outcome partless =
      run("register " + path("cube.prm") + " " + cube() + " --truth " + path("mugs/mug_003"));
  EXPECT_EQ(partless.exit_code, 1) << partless.output;
  EXPECT_NE(partless.output.find("the model has no parts"), std::string::npos) << partless.output;
}

TEST_F(Cli, RegisterWritesItsOutputsAndRefusesBadInput) {
  ASSERT_EQ(run("synth mug --out " + path("mugs") + " --instances 4 --seed 3").exit_code, 0);
  ASSERT_EQ(run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300").exit_code, 0);
  const std::string observed = path("mugs/ground_truth/mug_003.ply");
  write("frames.json", R"({"format": "partreg-frames", "version": 1, "frames": [{"name": "grasp",
      "position": [0.05, 0.05, 0.0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})");
  const Outcome good =
      run("register " + path("mug.prm") + " " + observed + " --variant hol+part --json " + path("r.json") +
          " --points-out " + path("p.ply") + " --mesh-out " + path("m.obj") + " --frames " +
          path("frames.json") + " --frames-out " + path("moved.json") + " --truth " + observed);
  ASSERT_EQ(good.exit_code, 0) << good.output;
  for (const char* file : {"r.json", "p.ply", "m.obj", "moved.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
  std::ifstream json(dir / "r.json");
  const std::string text{std::istreambuf_iterator<char>(json), {}};
  for (const char* key : {"T_observed_canonical", "latent", "eq5_per_diagonal2", "p90", "\"handle\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  // --truth scores the three baselines on the same observation, and the ratio to the oracle
  // template is partreg's figure over the oracle's.
  const nlohmann::json report = nlohmann::json::parse(text);
  const nlohmann::json& baselines = report.at("truth").at("baselines");
  for (const char* baseline : {"oracle-template", "rigid-canonical", "mean-shape"})
    EXPECT_GT(baselines.at(baseline).at("symmetric_rms_per_diagonal").get<double>(), 0.0) << baseline;
  EXPECT_NEAR(baselines.at("ratio_to_oracle_template").get<double>(),
              report.at("truth").at("symmetric_rms_per_diagonal").get<double>() /
                  baselines.at("oracle-template").at("symmetric_rms_per_diagonal").get<double>(),
              1e-12);
  EXPECT_LE(baselines.at("oracle-template").at("symmetric_rms_per_diagonal").get<double>(),
            baselines.at("rigid-canonical").at("symmetric_rms_per_diagonal").get<double>() + 1e-12)
      << "the oracle's templates include the canonical";

  // The search says how many hypotheses it tried (12 yaws x 9 tilts by default) and how clear the
  // winner was, in the JSON and on the command line.
  const nlohmann::json& holistic = report.at("spaces").at(0);
  EXPECT_EQ(holistic.at("pose_hypotheses").get<int>(), 108);
  EXPECT_GT(holistic.at("selection_score").get<double>(), 0.0);
  EXPECT_GE(holistic.at("runner_up_score").get<double>(), holistic.at("selection_score").get<double>());
  EXPECT_NE(good.output.find("pose: best of 108 hypotheses"), std::string::npos) << good.output;

  // How far the written mesh is stretched (core::mesh_stretch): hol+part on this mug stretches some edge of
  // the canonical 5.0x (measured; the synthetic mugs' handles differ much in size); measured in the wrong
  // units (the canonical's normalised mesh against the data's) it would read about 6 times more or less.
  EXPECT_NE(good.output.find("mesh stretch: largest edge "), std::string::npos) << good.output;
  EXPECT_GT(report.at("mesh_stretch").get<double>(), 1.5);
  EXPECT_LT(report.at("mesh_stretch").get<double>(), 10.0);

  // What the refinement (on by default) did; off, it says so and nothing more.
  const nlohmann::json& refinement = report.at("refinement");
  EXPECT_TRUE(refinement.at("enabled").get<bool>());
  EXPECT_TRUE(refinement.at("applied").get<bool>());
  EXPECT_GT(refinement.at("points").get<int>(), 0);
  EXPECT_GT(refinement.at("observed").get<int>(), refinement.at("points").get<int>() / 2) << "a full view";
  EXPECT_LE(refinement.at("observed").get<int>(), refinement.at("points").get<int>());
  EXPECT_GE(refinement.at("iterations").get<int>(), 1);
  // A clean surface (a real mug's two walls read as 0.014); the kernel is refine-beta or 4x the noise.
  const double noise = refinement.at("noise_normalised").get<double>();
  EXPECT_GT(noise, 0.0);
  EXPECT_LT(noise, 0.02);
  EXPECT_DOUBLE_EQ(refinement.at("kernel_width_normalised").get<double>(), std::max(0.05, 4.0 * noise));
  // w is refine-outliers (1e-5) or the share left out as strays: a clean scan has few.
  const double outlier_weight = refinement.at("outlier_weight").get<double>();
  EXPECT_GE(outlier_weight, 1e-5);
  EXPECT_LT(outlier_weight, 0.05);
  // A clean scan stays with closest points: the mixture (above mixture-noise, 0.03) did not run.
  const nlohmann::json& mixture = report.at("mixture");
  EXPECT_FALSE(mixture.at("applied").get<bool>());
  EXPECT_GT(mixture.at("noise_normalised").get<double>(), 0.0);
  EXPECT_LT(mixture.at("noise_normalised").get<double>(), 0.03);
  EXPECT_EQ(mixture.at("sigma_normalised").get<double>(), 0.0);
  EXPECT_GT(refinement.at("mean_movement_normalised").get<double>(), 0.0);
  EXPECT_GE(refinement.at("max_movement_normalised").get<double>(),
            refinement.at("mean_movement_normalised").get<double>());
  const Outcome off =
      run("register " + path("mug.prm") + " " + observed + " --no-refine --json " + path("off.json"));
  ASSERT_EQ(off.exit_code, 0) << off.output;
  std::ifstream off_json(dir / "off.json");
  EXPECT_EQ(nlohmann::json::parse(off_json).at("refinement"), nlohmann::json({{"enabled", false}}));

  write("few.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n");
  write("nan.xyz", "nan nan nan\n");
  std::string huge;
  for (int i = 0; i < 50; ++i) huge += std::to_string(i * 10.0) + " " + std::to_string(i % 7 * 10.0) + " 0\n";
  write("huge.xyz", huge);
  write("skewed.json", R"({"format": "partreg-frames", "version": 1, "frames": [{"name": "bad",
      "position": [0, 0, 0], "rotation": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]}]})");
  std::ifstream model_in(dir / "mug.prm", std::ios::binary);
  std::string model{std::istreambuf_iterator<char>(model_in), {}};
  const std::string version = "\"format_version\":" + std::to_string(io::kModelFormatVersion);
  model.replace(model.find(version), version.size(),
                "\"format_version\":" + std::to_string(io::kModelFormatVersion + 1));  // same length
  std::ofstream(dir / "v2.prm", std::ios::binary) << model;
  const std::string out = " --points-out " + path("out.ply");
  const std::vector<std::pair<std::string, int>> cases = {
      {"register " + path("mug.prm") + " " + path("few.xyz") + out, 1},
      {"register " + path("mug.prm") + " " + observed + " --restarts 0" + out, 2},
      {"register " + path("mug.prm") + " " + observed + " --max-tilt 3.5" + out, 2},
      {"register " + path("mug.prm") + " " + observed + " --max-tilt -0.1" + out, 2},
      {"register " + path("mug.prm") + " " + observed + " --up 0,0,0" + out, 2},
      {"register " + path("mug.prm") + " " + observed + " --viewpoint nan,0,0" + out, 2},
      {"register " + path("mug.prm") + " " + path("nan.xyz") + out, 1},
      {"register " + path("mug.prm") + " " + path("huge.xyz") + out, 1},
      {"register " + path("v2.prm") + " " + observed + out, 1},
      {"register " + path("mug.prm") + " " + observed + " --variant sideways" + out, 2},
      {"register " + path("mug.prm") + " " + observed + " --frames " + path("skewed.json") +
           " --frames-out " + path("x.json") + out,
       1},
  };
  for (const auto& [arguments, code] : cases) {
    const Outcome result = run(arguments);
    EXPECT_EQ(result.exit_code, code) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find("partreg: "), std::string::npos) << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.json"));
}

TEST_F(Cli, LabelAssignsFacesAndRefusesAnEmptySelection) {
  const std::string mesh = cube();
  const Outcome good = run("label " + mesh + " --part lid --box -1,-1,0.9,2,2,2 --out " + path("l.json"));
  ASSERT_EQ(good.exit_code, 0) << good.output;
  EXPECT_NE(good.output.find("part lid: 2 faces"), std::string::npos) << good.output;
  EXPECT_EQ(run("label " + mesh + " --part lid --box 5,5,5,6,6,6 --out " + path("none.json")).exit_code, 1);
  EXPECT_EQ(run("label " + mesh + " --part lid --box 0,0,0,1,1,1 --sphere 0,0,0,1 --out " + path("two.json"))
                .exit_code,
            2);
  EXPECT_EQ(run("label " + mesh + " --part lid --sphere 0,0,0,-1 --out " + path("neg.json")).exit_code, 2);
  // The library names the value, the command adds the flag that carried it.
  const Outcome zero_normal =
      run("label " + mesh + " --part lid --plane 0,0,0,0,0,0 --out " + path("z.json"));
  EXPECT_EQ(zero_normal.exit_code, 2);
  EXPECT_NE(zero_normal.output.find("partreg: --plane: the plane's normal 0,0,0 has zero length"),
            std::string::npos)
      << zero_normal.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "none.json"));
}

}  // namespace
}  // namespace partreg
