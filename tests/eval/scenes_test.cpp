// `partreg eval --scenes N` end to end on a synthetic category: depth scenes beside the point-sampled views.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

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

TEST(EvalScenes, TheSceneCutChoosesTheHeldOutMugAndRegistersNearlyAsWellAsTheHandCut) {
  testing::TempDir dir;
  const std::string data = (dir / "mugs").string(), out = (dir / "eval").string();
  ASSERT_EQ(run("synth mug --instances 4 --seed 3 --correspondences 300 --out " + data).exit_code, 0);
  // Full views only (no partial views, no sweeps, no baselines), 2 tested mugs, 3 scenes each.
  const Outcome result = run("eval " + data +
                             " --protocol quick --variants holistic --sweeps none --views 0 --no-baselines "
                             "--threads 2 --scenes 3 --out " +
                             out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / "eval" / "results.csv");
  // 2 tested mugs x (1 full view + 3 scenes x 2 cuts).
  ASSERT_EQ(rows.size(), 2u * (1 + 3 * 2));

  std::map<std::tuple<std::string, int>, std::map<eval::CutKind, const eval::EvalRow*>> scenes;
  for (const eval::EvalRow& row : rows)
    if (row.scene) scenes[{row.instance, row.view}][row.scene->cut] = &row;
  ASSERT_EQ(scenes.size(), 6u);
  int right = 0;
  double scene_sum = 0.0, hand_sum = 0.0;
  for (const auto& [key, cuts] : scenes) {
    ASSERT_EQ(cuts.size(), 2u);
    const eval::EvalRow& scene = *cuts.at(eval::CutKind::scene);
    const eval::EvalRow& hand = *cuts.at(eval::CutKind::hand);
    // The hand cut is the true mask: overlap 1 by construction; a scene cut of the right mug loses only its
    // foot (within the plane distance of the table) and edge pixels.
    EXPECT_DOUBLE_EQ(hand.scene->overlap, 1.0);
    EXPECT_DOUBLE_EQ(hand.scene->precision, 1.0);
    right += scene.scene->precision >= eval::kRightObjectPrecision;
    EXPECT_GT(hand.observed_points, 500);
    // Both registrations land on the held-out mug in the camera frame: a truth left in the mug's own frame
    // (or in metres instead of data units) would be off by about its own diagonal, far above 10%.
    ASSERT_TRUE(std::isfinite(hand.errors.symmetric_rms_per_diagonal));
    EXPECT_LT(hand.errors.symmetric_rms_per_diagonal, 0.10)
        << std::get<0>(key) << " scene " << std::get<1>(key);
    if (scene.scene->precision >= eval::kRightObjectPrecision) {
      EXPECT_GT(scene.scene->overlap, 0.8);  // the whole mug, not a piece of it
      // ... but never all of it: the foot within the plane distance of the table goes with the plane (an
      // overlap of 1 would say the cut's pixels were never compared with the mask's).
      EXPECT_LT(scene.scene->overlap, 0.99);
      EXPECT_LT(scene.observed_points, hand.observed_points);
      scene_sum += scene.errors.symmetric_rms_per_diagonal,
          hand_sum += hand.errors.symmetric_rms_per_diagonal;
    }
  }
  // The mug stands in the middle of the image, its neighbours 0.2 m to either side: the pick nearest the
  // image centre must find it in (nearly) every scene.
  EXPECT_GE(right, 5);
  const double ratio = scene_sum / hand_sum;
  ASSERT_TRUE(std::isfinite(ratio));
  EXPECT_LT(ratio, 1.5);
  EXPECT_GT(ratio, 0.67);

  // The report: a Depth scenes table with the 6 scenes, and the full views' table without the scene rows.
  const std::string tables = read_text(dir / "eval" / "tables.md");
  EXPECT_NE(tables.find("\nDepth scenes (eval --scenes): "), std::string::npos) << tables;
  EXPECT_NE(tables.find("| mugs | holistic | 6 | " + std::to_string(right) + " ("), std::string::npos)
      << tables;
  double full = 0.0;
  for (const eval::EvalRow& row : rows)
    if (!row.scene) full += row.errors.symmetric_rms_per_diagonal / 2;
  EXPECT_DOUBLE_EQ(eval::mean_symmetric_rms_per_diagonal(rows, "mugs", "holistic", false), full);
  const nlohmann::json run_json = nlohmann::json::parse(read_text(dir / "eval" / "run.json"));
  EXPECT_EQ(run_json["depth_scenes"]["per_instance"], 3);
  EXPECT_EQ(run_json["results_format"], eval::kRowsFormat);
}

TEST(EvalScenes, BadSceneSettingsAreRefusedWithOneLine) {
  testing::TempDir dir;
  for (const char* flags :
       {"--scenes -1", "--scenes x", "--scene-size 0", "--scene-size 20", "--cluster-tolerance 0"}) {
    const Outcome result =
        run("eval " + (dir / "none").string() + " --out " + (dir / "out").string() + " " + flags);
    EXPECT_EQ(result.exit_code, 2) << flags << ": " << result.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << flags;
  }
}

}  // namespace
}  // namespace partreg
