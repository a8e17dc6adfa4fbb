// `partreg eval` end to end on a synthetic category (quick protocol), and its refusals of bad input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>

#include "partreg/core/errors.hpp"
#include "partreg/eval/protocol.hpp"
#include "partreg/eval/report.hpp"
#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

using testing::Outcome;

Outcome run(const std::string& arguments) { return testing::run_partreg(arguments); }

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string two_decimals(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << value;
  return out.str();
}

TEST(EvalCommand, QuickProtocolOnASyntheticCategoryWritesRowsTablesAndPlotsThatAgree) {
  testing::TempDir dir;
  const std::string data = (dir / "mugs").string(), out = (dir / "eval").string();
  ASSERT_EQ(run("synth mug --instances 5 --out " + data).exit_code, 0);
  // The paper's three variants (eval's default runs every variant, coupled too).
  const Outcome result =
      run("eval " + data + " --protocol quick --variants holistic,partwise,hol+part --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find(" rows, "), std::string::npos);             // the progress lines
  EXPECT_NE(result.output.find(" baseline rows in "), std::string::npos);  // the summary
  for (const char* file :
       {"results.csv", "tables.md", "run.json", "mugs_full_sweeps.png", "mugs_partial_sweeps.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "eval" / file)) << file;

  const std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / "eval" / "results.csv");
  // 2 tested instances x (1 full + 12 views + 3 observations x 4 kinds x 3 levels) x (3 variants + 4
  // baselines).
  EXPECT_EQ(rows.size(), 2u * (13 + 36) * 7);
  for (const eval::EvalRow& row : rows) {
    ASSERT_TRUE(std::isfinite(row.errors.symmetric_rms_per_diagonal));
    // Most templates, and the true shape, lack the canonical's rows and parts.
    if (row.variant == "oracle-template" || row.variant == "true-shape") continue;
    ASSERT_TRUE(row.errors.correspondence_per_diagonal) << "synthetic data has ground-truth correspondences";
    ASSERT_TRUE(std::isfinite(row.errors.eq5_per_diagonal2));
    ASSERT_EQ(row.errors.part_eq5_per_diagonal2.size(), 2u);  // body, handle
    // The synthetic mugs have part folders: each registration is also scored part against own part (the
    // baselines are not: a template's parts are not the canonical's).
    const bool registration =
        row.variant == "holistic" || row.variant == "partwise" || row.variant == "hol+part";
    ASSERT_EQ(row.errors.own_part_rms_per_diagonal.size(), registration ? 2u : 0u) << row.variant;
    if (registration) EXPECT_TRUE(std::isfinite(*row.errors.own_part_rms_mean_per_diagonal));
    // Each registration says how far it stretched the canonical mesh. The synthetic mugs' handles differ
    // much in size, so some edge always lengthens: clean full views measured 1.96-3.41x (a space's own grid
    // of 4 such mugs reaches 4.2x; partial views, where partwise's parts roam, up to 7.1x). An edge measured
    // in the wrong units (the canonical's normalised mesh against the data's) would be off by the model's
    // scale, about 6x.
    ASSERT_EQ(row.mesh_stretch.has_value(), registration) << row.variant;
    if (registration && row.view < 0 && row.perturbation == eval::Perturbation::none) {
      EXPECT_GT(*row.mesh_stretch, 1.0) << row.variant;
      EXPECT_LT(*row.mesh_stretch, 4.5) << row.variant;
    }
  }
  // Every observation has its four baselines; the oracle (which may pick the canonical) is never worse than
  // the rigid canonical on the same observation, and the true shape (the tested mug itself at its true pose,
  // whatever the perturbation did to the observation) is below both.
  std::map<std::tuple<std::string, int, int, int>, std::map<std::string, double>> by_observation;
  for (const eval::EvalRow& row : rows)
    by_observation[std::make_tuple(row.instance, row.view, static_cast<int>(row.perturbation),
                                   row.level_index)][row.variant] = row.errors.symmetric_rms_per_diagonal;
  EXPECT_EQ(by_observation.size(), 2u * (13 + 36));
  for (const auto& [observation, figures] : by_observation) {
    ASSERT_EQ(figures.size(), 7u);
    EXPECT_LE(figures.at("oracle-template"), figures.at("rigid-canonical") + 1e-12);
    EXPECT_LT(figures.at("true-shape"), figures.at("oracle-template"));
  }
  // The tables are the CSV's means: Table 1 and Table 2 rows recomputed from the rows.
  const std::string tables = read_text(dir / "eval" / "tables.md");
  for (bool partial : {false, true}) {
    std::string line = "| mugs |";
    for (const char* variant : {"holistic", "partwise", "hol+part"})
      line += " " + two_decimals(1e4 * eval::mean_eq5_per_diagonal2(rows, "mugs", variant, partial)) + " |";
    EXPECT_NE(tables.find(line), std::string::npos) << line << "\n" << tables;
  }
  // The registrations did something: a fully observed mug is matched far better than by chance
  // (a canonical mug dropped at the wrong place scores above 1e-2).
  EXPECT_LT(eval::mean_eq5_per_diagonal2(rows, "mugs", "hol+part", false), 2e-3);
  // So did the rigid baselines: the oracle's aligned template is close to the truth (measured 3.3% of the
  // diagonal) but, being rigid, not as close as partreg's deformed canonical on a full view (measured 2.6%).
  const double oracle = eval::mean_symmetric_rms_per_diagonal(rows, "mugs", "oracle-template", false);
  EXPECT_LT(oracle, 0.05);
  EXPECT_LT(eval::mean_symmetric_rms_per_diagonal(rows, "mugs", "hol+part", false), oracle);
  // The baseline tables are the CSV's means: % of the diagonal, then each variant over the oracle template.
  const std::vector<std::string> variants = {"holistic", "partwise", "hol+part"};
  for (bool partial : {false, true}) {
    const auto mean = [&](const std::string& method) {
      return eval::mean_symmetric_rms_per_diagonal(rows, "mugs", method, partial);
    };
    std::string line = "| mugs |";
    for (const char* method : {"holistic", "partwise", "hol+part", "oracle-template", "rigid-canonical",
                               "mean-shape", "true-shape"})
      line += " " + two_decimals(100 * mean(method)) + " |";
    for (const std::string& variant : variants)
      line += " " + two_decimals(mean(variant) / mean("oracle-template")) + " |";
    EXPECT_NE(tables.find(line + "\n"), std::string::npos) << line << "\n" << tables;
  }
}

TEST(EvalCommand, NoBaselinesLeavesOnlyTheVariantsRows) {
  testing::TempDir dir;
  const std::string data = (dir / "mugs").string(), out = (dir / "eval").string();
  ASSERT_EQ(run("synth mug --instances 4 --out " + data).exit_code, 0);
  const Outcome result =
      run("eval " + data +
          " --protocol quick --views 0 --levels 1 --variants holistic --no-baselines --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / "eval" / "results.csv");
  EXPECT_EQ(rows.size(), 2u * (1 + 4));  // 2 instances x (full view + 4 kinds x 1 level), holistic only
  const Outcome clean =
      run("eval " + data + " --protocol quick --views 0 --sweeps none --variants holistic " +
          "--no-baselines --out " + (dir / "clean").string());
  ASSERT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_EQ(eval::read_rows_csv(dir / "clean" / "results.csv").size(), 2u);  // the clean full views only
  EXPECT_TRUE(eval::baselines_of(rows).empty());
  EXPECT_EQ(read_text(dir / "eval" / "tables.md").find("Against the baselines"), std::string::npos);
}

// The library refuses what the command line's checks keep from it: a negative sample count would otherwise be
// a huge allocation.
TEST(EvalSettings, SampleCountsOutOfRangeAreRefused) {
  eval::EvalInput input;
  input.category = "points";
  for (const char* name : {"a", "b", "c"}) {
    core::TrainingInstance instance;
    instance.name = name;
    instance.points = core::Points::Random(20, 3);
    input.instances.push_back(instance);
  }
  eval::EvalSettings settings;
  EXPECT_EQ(eval::tested_instances(input, settings).size(), 3u);
  settings.truth_points = 0;  // the training sample: allowed
  EXPECT_EQ(eval::tested_instances(input, settings).size(), 3u);
  settings.truth_points = -1;
  EXPECT_THROW(eval::tested_instances(input, settings), UsageError);
  settings.truth_points = core::kTruthSamples, settings.full_view_points = 0;
  EXPECT_THROW(eval::tested_instances(input, settings), UsageError);
}

// A mesh instance's truth is a dense sample of its own, parts included: the true shape's forward half (its
// points to the nearest truth point) is bounded by the truth's spacing, which the training sample of 4000
// points would set (docs/evaluation.md, "The truth").
TEST(EvalCommand, TheTruthIsADenseSampleOfItsOwnWithItsParts) {
  testing::TempDir dir;
  const std::string data = (dir / "mugs").string();
  ASSERT_EQ(run("synth mug --instances 4 --out " + data).exit_code, 0);
  const auto true_shapes = [&](const std::string& name, const std::string& truth) {
    const Outcome result =
        run("eval " + data + " --protocol quick --views 0 --sweeps none --variants hol+part " + truth +
            " --out " + (dir / name).string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / name / "results.csv");
    EXPECT_EQ(rows.size(), 2u * 5);  // 2 instances x (hol+part + 4 baselines)
    return rows;
  };
  const std::vector<eval::EvalRow> dense = true_shapes("dense", ""),
                                   sampled = true_shapes("sampled", "--truth-samples 0");
  ASSERT_EQ(dense.size(), sampled.size());
  for (std::size_t r = 0; r < dense.size(); ++r) {
    // The same instance, measured on another sample of its surface: the diagonal barely moves.
    EXPECT_NEAR(dense[r].diagonal, sampled[r].diagonal, 0.02 * sampled[r].diagonal);
    if (dense[r].variant == "true-shape") {
      // Measured 0.44% against 0.97-1.00% of the diagonal: the spacing of 20000 points against 4000.
      EXPECT_LT(dense[r].errors.forward_rms_per_diagonal(),
                0.6 * sampled[r].errors.forward_rms_per_diagonal());
    }
    if (dense[r].variant ==
        "hol+part") {  // the dense truth carries its parts: each is scored against its own
      EXPECT_EQ(dense[r].errors.own_part_rms_per_diagonal.size(), 2u);
      EXPECT_LT(*dense[r].errors.own_part_rms_mean_per_diagonal, 0.05);
    }
  }
  EXPECT_NE(read_text(dir / "dense" / "run.json").find("\"truth_samples\": 20000"), std::string::npos);
  EXPECT_NE(read_text(dir / "sampled" / "run.json").find("\"truth_samples\": 0"), std::string::npos);
}

// The sweeps the paper lacks: yaw all round the up axis (the pose search makes it flat) and rotation past
// 0.65 rad.
TEST(EvalCommand, YawAndWideRotationSweepsRunEveryLevelAndReachTheTables) {
  testing::TempDir dir;
  const std::string data = (dir / "mugs").string(), out = (dir / "eval").string();
  ASSERT_EQ(run("synth mug --instances 4 --out " + data).exit_code, 0);
  const Outcome result = run("eval " + data +
                             " --protocol quick --views 0 --levels 1 --sweeps yaw,rotation --wide-rotation"
                             " --variants holistic --no-baselines --out " +
                             out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / "eval" / "results.csv");
  EXPECT_EQ(rows.size(), 2u * (1 + 12 + 1 + 5));  // full view, 12 yaws, rotation: level 1 and 5 wide levels
  std::map<int, std::vector<double>> yaw_errors;
  for (const eval::EvalRow& row : rows)
    if (row.perturbation == eval::Perturbation::yaw)
      yaw_errors[row.level_index].push_back(row.errors.symmetric_rms_per_diagonal);
  ASSERT_EQ(yaw_errors.size(), 12u);
  const auto mean = [](const std::vector<double>& v) { return (v[0] + v[1]) / 2; };
  for (const auto& [level, errors] : yaw_errors)  // within 15% of the error at yaw 0
    EXPECT_LT(mean(errors), 1.15 * mean(yaw_errors[0]) + 1e-3) << "yaw level " << level;
  const std::string tables = read_text(dir / "eval" / "tables.md");
  EXPECT_NE(tables.find("| yaw 330 deg |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| rotation 1.57 |"), std::string::npos) << tables;
  const std::string run_json = read_text(dir / "eval" / "run.json");
  EXPECT_NE(run_json.find("\"wide_rotation\": true"), std::string::npos) << run_json;
  EXPECT_NE(run_json.find("\"yaw\""), std::string::npos) << run_json;
}

TEST(EvalCommand, BadInputIsRefusedAndNothingIsOverwritten) {
  testing::TempDir dir;
  const std::string small = (dir / "two").string();
  ASSERT_EQ(run("synth mug --instances 2 --out " + small).exit_code, 0);
  Outcome result = run("eval " + small + " --protocol quick --out " + (dir / "a").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("at least 3"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));

  result = run("eval " + small + " --variants holistic,sideways --out " + (dir / "b").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("sideways"), std::string::npos) << result.output;

  result = run("eval " + small + " --levels 1,7 --out " + (dir / "c").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("1 to 5"), std::string::npos) << result.output;

  for (const char* sweeps : {"none,yaw", "shear"}) {
    result = run("eval " + small + " --sweeps " + sweeps + " --out " + (dir / "e").string());
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_NE(result.output.find(std::string(sweeps).substr(0, 4)), std::string::npos) << result.output;
  }

  std::filesystem::create_directories(dir / "taken");
  std::ofstream(dir / "taken" / "notes.txt") << "mine";
  result = run("eval " + small + " --out " + (dir / "taken").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("not empty"), std::string::npos) << result.output;
  EXPECT_EQ(read_text(dir / "taken" / "notes.txt"), "mine");
  for (const std::string& entry : dir.entries())
    EXPECT_EQ(entry.find(".partial"), std::string::npos) << entry;

  result = run("eval " + (dir / "missing").string() + " --out " + (dir / "d").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
}

}  // namespace
}  // namespace partreg
