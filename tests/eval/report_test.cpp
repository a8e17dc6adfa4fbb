// Errors on hand-made sets, and the CSV and tables the evaluation writes.
#include "partreg/eval/report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

TEST(RegistrationErrors, MatchTheHandComputedValues) {
  // Truth: three points on the x axis; deformed: two points, 0.5 and 1.0 off the closest truth point.
  core::Points truth(3, 3);
  truth << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  core::Points deformed(2, 3);
  deformed << 0, 0.5, 0, 2, 0, 1;
  const Eigen::VectorXi part = (Eigen::VectorXi(2) << 0, 1).finished();
  core::Points true_rows(2, 3);
  true_rows << 0, 0, 0, 1, 0, 0;  // where the two deformed points should have been
  const double diagonal = 2.0;
  const core::TruthErrors e =
      core::measure_against_truth(deformed, part, {"body", "handle"}, truth, diagonal, &true_rows);
  EXPECT_DOUBLE_EQ(e.eq5, (0.25 + 1.0) / 2);  // Eq. 5: mean squared closest-point distance
  EXPECT_DOUBLE_EQ(e.eq5_per_diagonal2, 0.625 / 4);
  EXPECT_DOUBLE_EQ(e.part_eq5_per_diagonal2.at("body"), 0.25 / 4);
  EXPECT_DOUBLE_EQ(e.part_eq5_per_diagonal2.at("handle"), 1.0 / 4);
  // Chamfer: deformed->truth (0.5 + 1) / 2; truth->deformed (0.5 + sqrt(1.25) + 1) / 3; halved sum.
  const double chamfer = ((0.5 + 1.0) / 2 + (0.5 + std::sqrt(1.25) + 1.0) / 3) / 2;
  EXPECT_NEAR(e.chamfer, chamfer, 1e-12);
  EXPECT_NEAR(e.chamfer_per_diagonal, chamfer / 2, 1e-12);
  ASSERT_TRUE(e.correspondence_per_diagonal);
  EXPECT_NEAR(*e.correspondence_per_diagonal, (0.5 + std::sqrt(2.0)) / 2 / 2, 1e-12);
  EXPECT_THROW(core::measure_against_truth(core::Points(0, 3), part, {}, truth, 1.0), InputError);
}

eval::EvalRow row(const std::string& variant, int view, eval::Perturbation kind, int level, double eq5) {
  eval::EvalRow r;
  r.category = "mugs", r.instance = "mug_1", r.canonical = "mug_0", r.variant = variant, r.view = view;
  r.perturbation = kind, r.level_index = level, r.diagonal = 0.3;
  r.errors.eq5_per_diagonal2 = eq5, r.errors.eq5 = eq5 * 0.09;
  r.errors.part_eq5_per_diagonal2 = {{"body", eq5 / 2}, {"handle", eq5 * 2}};
  return r;
}

TEST(EvalReport, CsvRoundTripsAndTablesShowTheMeans) {
  std::vector<eval::EvalRow> rows = {row("holistic", -1, eval::Perturbation::none, -1, 4e-4),
                                     row("holistic", -1, eval::Perturbation::none, -1, 6e-4),
                                     row("hol+part", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("holistic", 3, eval::Perturbation::none, -1, 9e-4),
                                     row("holistic", -1, eval::Perturbation::noise, 2, 7e-4)};
  rows[2].errors.correspondence_per_diagonal = 0.012;
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_DOUBLE_EQ(back[1].errors.eq5_per_diagonal2, 6e-4);
  EXPECT_DOUBLE_EQ(back[0].errors.part_eq5_per_diagonal2.at("handle"), 8e-4);
  EXPECT_EQ(back[4].perturbation, eval::Perturbation::noise);
  EXPECT_TRUE(back[2].errors.correspondence_per_diagonal);
  EXPECT_FALSE(back[0].errors.correspondence_per_diagonal);

  EXPECT_DOUBLE_EQ(eval::mean_eq5_per_diagonal2(back, "mugs", "holistic", false), 5e-4);  // full, clean only
  EXPECT_DOUBLE_EQ(eval::mean_eq5_per_diagonal2(back, "mugs", "holistic", true), 9e-4);
  const std::string tables = eval::markdown_report(back);
  EXPECT_NE(tables.find("| mugs | 5.00 | 3.00 |"), std::string::npos) << tables;  // Table 1 (x 1e4)
  EXPECT_NE(tables.find("| mugs | 9.00 | - |"), std::string::npos) << tables;     // Table 2
  EXPECT_NE(tables.find("| noise 0.015 | 7.00 | - |"), std::string::npos) << tables;
  EXPECT_TRUE(eval::write_sweep_plot(dir / "full.png", back, "mugs", false));
  EXPECT_GT(std::filesystem::file_size(dir / "full.png"), 10000u);
  EXPECT_FALSE(eval::write_sweep_plot(dir / "partial.png", back, "mugs", true));  // no partial sweep
}

eval::EvalRow rms_row(const std::string& method, int view, double rms, double eq5 = 1e-4) {
  eval::EvalRow r = row(method, view, eval::Perturbation::none, -1, eq5);
  r.errors.symmetric_rms_per_diagonal = rms;
  return r;
}

TEST(EvalReport, TheHeadlineFigureShowsWithItsForwardAndReverseHalves) {
  // Diagonal 0.5. Full views: forward 0.02 / reverse 0.04 (symmetric 0.03) and 0.04 / 0.06 (0.05): means
  // 0.03 / 0.05, symmetric 0.04. A perturbed row stays out.
  const auto halves_row = [](double forward, double reverse, eval::Perturbation kind) {
    eval::EvalRow r = row("coupled", -1, kind, kind == eval::Perturbation::none ? -1 : 0, 0.0);
    r.diagonal = r.errors.diagonal = 0.5;
    r.errors.eq5 = std::pow(forward * 0.5, 2), r.errors.reverse_eq5 = std::pow(reverse * 0.5, 2);
    r.errors.eq5_per_diagonal2 = forward * forward;
    r.errors.symmetric_rms_per_diagonal = 0.5 * (forward + reverse);
    return r;
  };
  const std::vector<eval::EvalRow> rows = {halves_row(0.02, 0.04, eval::Perturbation::none),
                                           halves_row(0.04, 0.06, eval::Perturbation::none),
                                           halves_row(0.5, 0.5, eval::Perturbation::noise)};
  EXPECT_DOUBLE_EQ(rows[0].errors.forward_rms_per_diagonal(), 0.02);
  EXPECT_DOUBLE_EQ(rows[0].errors.reverse_rms_per_diagonal(), 0.04);
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::string tables = eval::markdown_report(eval::read_rows_csv(dir / "r.csv"));
  EXPECT_NE(tables.find("full views (forward / reverse half):\n\n| category | coupled |\n|---|---|\n"
                        "| mugs | 4.000 (3.00 / 5.00) |"),
            std::string::npos)
      << tables;
  EXPECT_EQ(tables.find("partial views (forward / reverse half)"), std::string::npos) << tables;  // none
}

TEST(EvalReport, BaselineTableShowsTheMeansAndRatiosOfTheRowsAndLeavesTheEq5TablesAlone) {
  // Full views: holistic 0.02 and 0.03 (mean 0.025), the oracle 0.04 and 0.06 (mean 0.05): ratio 0.50.
  // Partial views: holistic 0.045 against the oracle's 0.03: ratio 1.50.
  std::vector<eval::EvalRow> rows = {rms_row("holistic", -1, 0.02),
                                     rms_row("holistic", -1, 0.03),
                                     rms_row("oracle-template", -1, 0.04, 9e-3),
                                     rms_row("oracle-template", -1, 0.06, 9e-3),
                                     rms_row("rigid-canonical", -1, 0.08),
                                     rms_row("mean-shape", -1, 0.07),
                                     rms_row("holistic", 2, 0.045),
                                     rms_row("oracle-template", 2, 0.03, 9e-3),
                                     rms_row("rigid-canonical", 2, 0.05),
                                     rms_row("mean-shape", 2, 0.06)};
  // A perturbed row is not a clean observation: it must not enter the means.
  eval::EvalRow swept = rms_row("oracle-template", -1, 0.9);
  swept.perturbation = eval::Perturbation::noise, swept.level_index = 0;
  rows.push_back(swept);
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  EXPECT_EQ(eval::variants_of(back), std::vector<std::string>{"holistic"});
  EXPECT_EQ(eval::baselines_of(back),
            (std::vector<std::string>{"oracle-template", "rigid-canonical", "mean-shape"}));
  EXPECT_DOUBLE_EQ(eval::mean_symmetric_rms_per_diagonal(back, "mugs", "oracle-template", false), 0.05);

  const std::string tables = eval::markdown_report(back);
  // Columns: holistic, the three baselines (% of the diagonal), then holistic / oracle-template.
  EXPECT_NE(tables.find("| category | holistic | oracle-template | rigid-canonical | mean-shape | "
                        "holistic / oracle-template |"),
            std::string::npos)
      << tables;
  EXPECT_NE(tables.find("| mugs | 2.50 | 5.00 | 8.00 | 7.00 | 0.50 |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| mugs | 4.50 | 3.00 | 5.00 | 6.00 | 1.50 |"), std::string::npos) << tables;
  // Table 1 shows the holistic rows' Eq. 5 alone (1.00 x 1e4): the oracle's 9e-3 would show as a column.
  EXPECT_NE(tables.find("Table 1: mean Eq. 5 x 1e4, fully observed instances\n\n| category | holistic |\n"
                        "|---|---|\n| mugs | 1.00 |"),
            std::string::npos)
      << tables;
  EXPECT_NE(tables.find("Registrations: 3 (and 8 baseline rows"), std::string::npos) << tables;
}

TEST(EvalReport, SeamGapsRoundTripAndShowForThePartVariantsOnly) {
  // hol+part: two full views with mean gaps 1% and 3% (largest 2% and 6%): the table shows 2.00 / 4.00.
  std::vector<eval::EvalRow> rows = {row("holistic", -1, eval::Perturbation::none, -1, 4e-4),
                                     row("hol+part", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("hol+part", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("hol+part", 2, eval::Perturbation::none, -1, 3e-4),
                                     row("hol+part", -1, eval::Perturbation::noise, 0, 3e-4)};
  rows[1].seam = core::SeamGap{0.02, 0.01, 40};
  rows[2].seam = core::SeamGap{0.06, 0.03, 40};
  rows[3].seam = core::SeamGap{0.5, 0.25, 40};
  rows[4].seam = core::SeamGap{0.9, 0.9, 40};  // perturbed: not in the clean table
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_FALSE(back[0].seam);
  ASSERT_TRUE(back[2].seam);
  EXPECT_DOUBLE_EQ(back[2].seam->mean, 0.03);
  EXPECT_DOUBLE_EQ(back[2].seam->max, 0.06);
  const std::string tables = eval::markdown_report(back);
  const auto full = tables.find(
      "Seam gap (core::seam_gap), mean / largest over the boundary points, % of the "
      "model's diagonal, full views\n\n| category | hol+part |\n|---|---|\n"
      "| mugs | 2.00 / 4.00 |");
  EXPECT_NE(full, std::string::npos) << tables;
  EXPECT_NE(tables.find("| mugs | 25.00 / 50.00 |"), std::string::npos) << tables;  // the partial view

  // Format 2 (before the seam columns), 3 (before the own-part columns) and 4 (before the mesh stretch) files
  // still read. The holistic row ends in 5 empty fields: seam gaps, own-part figures, stretch.
  // Plain CSV (pandas.read_csv without options): the header first, as many fields as every row, no comment
  // line.
  std::ifstream in(dir / "r.csv");
  std::string header, line;
  std::getline(in, header), std::getline(in, line);
  const auto fields = [](const std::string& text) { return std::count(text.begin(), text.end(), ',') + 1; };
  EXPECT_EQ(header.rfind("category,instance,canonical,", 0), 0u) << header;
  EXPECT_EQ(fields(header), fields(line));
  for (std::string next; std::getline(in, next);) EXPECT_EQ(fields(next), fields(header)) << next;
  EXPECT_EQ(header.find('#'), std::string::npos);
  const auto header_before = [&](const char* column) { return header.substr(0, header.rfind(column)); };
  // Every trailing field of this row is empty: the older layouts drop them, and the 7 grasp, 7 verdict and 3
  // depth-scene columns after them.
  const std::size_t later = 7 + 7 + 3;
  const auto line_without = [&](std::size_t empty_fields) {
    return line.substr(0, line.size() - empty_fields);
  };
  std::ofstream(dir / "v2.csv") << "# partreg evaluation rows, format 2\n"
                                << header_before(",seam_gap_mean") << "\n"
                                << line_without(5 + later) << "\n";
  std::ofstream(dir / "v3.csv") << "# partreg evaluation rows, format 3\n"
                                << header_before(",own_part_rms_mean") << "\n"
                                << line_without(3 + later) << "\n";
  std::ofstream(dir / "v4.csv") << "# partreg evaluation rows, format 4\n"
                                << header_before(",mesh_stretch_max") << "\n"
                                << line_without(1 + later) << "\n";
  std::ofstream(dir / "v5.csv") << "# partreg evaluation rows, format 5\n"
                                << header_before(",grasps,grasps_held") << "\n"
                                << line_without(later) << "\n";
  EXPECT_EQ(eval::read_rows_csv(dir / "v5.csv").size(), 1u);
  std::ofstream(dir / "v7.csv") << header_before(",verdict,inlier_share") << "\n"
                                << line_without(7 + 3) << "\n";
  EXPECT_EQ(eval::read_rows_csv(dir / "v7.csv").size(), 1u);
  std::ofstream(dir / "v8.csv") << header_before(",scene_cut,scene_overlap") << "\n"
                                << line_without(3) << "\n";
  ASSERT_EQ(eval::read_rows_csv(dir / "v8.csv").size(), 1u);
  EXPECT_FALSE(eval::read_rows_csv(dir / "v8.csv")[0].scene);
  std::ofstream(dir / "other.csv") << header << ",extra\n" << line << ",1\n";
  EXPECT_THROW(eval::read_rows_csv(dir / "other.csv"), InputError);
  for (const char* file : {"v2.csv", "v3.csv", "v4.csv"}) {
    const std::vector<eval::EvalRow> older = eval::read_rows_csv(dir / file);
    ASSERT_EQ(older.size(), 1u) << file;
    EXPECT_FALSE(older[0].seam);
    EXPECT_FALSE(older[0].errors.own_part_rms_mean_per_diagonal);
    EXPECT_FALSE(older[0].mesh_stretch);
    EXPECT_DOUBLE_EQ(older[0].errors.eq5_per_diagonal2, 4e-4);
  }
}

TEST(EvalReport, MeshStretchRoundTripsAndShowsItsMeanAndLargest) {
  // coupled, full views stretched 1.5x and 2.5x (mean 2.00, largest 2.50); a perturbed row and the baseline
  // are not in the clean table, which holistic (no stretch recorded) does not join either.
  std::vector<eval::EvalRow> rows = {row("coupled", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("coupled", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("coupled", -1, eval::Perturbation::noise, 0, 3e-4),
                                     row("holistic", -1, eval::Perturbation::none, -1, 3e-4),
                                     row("oracle-template", -1, eval::Perturbation::none, -1, 5e-4)};
  rows[0].mesh_stretch = 1.5;
  rows[1].mesh_stretch = 2.5;
  rows[2].mesh_stretch = 9.0;
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  ASSERT_EQ(back.size(), rows.size());
  ASSERT_TRUE(back[1].mesh_stretch);
  EXPECT_DOUBLE_EQ(*back[1].mesh_stretch, 2.5);
  EXPECT_FALSE(back[3].mesh_stretch);
  const std::string tables = eval::markdown_report(back);
  EXPECT_NE(
      tables.find("deformed / canonical edge length), mean / largest over the registrations, full views\n\n"
                  "| category | coupled |\n|---|---|\n| mugs | 2.00 / 2.50 |"),
      std::string::npos)
      << tables;
  EXPECT_NE(tables.find("partial views\n\n| category | coupled |\n|---|---|\n| mugs | - / - |"),
            std::string::npos)
      << tables;
}

TEST(EvalReport, OwnPartFiguresRoundTripAndShowPerPartAndTheirMean) {
  // coupled, full views: handle 10% and 30% (mean 20%), body 2% both, means over parts 6% and 16% (11%).
  std::vector<eval::EvalRow> rows = {row("coupled", -1, eval::Perturbation::none, -1, 4e-4),
                                     row("coupled", -1, eval::Perturbation::none, -1, 4e-4),
                                     row("coupled", -1, eval::Perturbation::noise, 0, 4e-4),
                                     row("oracle-template", -1, eval::Perturbation::none, -1, 4e-4)};
  rows[0].errors.own_part_rms_per_diagonal = {{"body", 0.02}, {"handle", 0.1}};
  rows[0].errors.own_part_rms_mean_per_diagonal = 0.06;
  rows[1].errors.own_part_rms_per_diagonal = {{"body", 0.02}, {"handle", 0.3}};
  rows[1].errors.own_part_rms_mean_per_diagonal = 0.16;
  rows[2].errors.own_part_rms_per_diagonal = {{"body", 0.9}, {"handle", 0.9}};  // perturbed: not shown
  rows[2].errors.own_part_rms_mean_per_diagonal = 0.9;
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  ASSERT_EQ(back.size(), rows.size());
  ASSERT_TRUE(back[1].errors.own_part_rms_mean_per_diagonal);
  EXPECT_DOUBLE_EQ(*back[1].errors.own_part_rms_mean_per_diagonal, 0.16);
  EXPECT_DOUBLE_EQ(back[1].errors.own_part_rms_per_diagonal.at("handle"), 0.3);
  EXPECT_FALSE(back[3].errors.own_part_rms_mean_per_diagonal);
  EXPECT_TRUE(back[3].errors.own_part_rms_per_diagonal.empty());
  const std::string tables = eval::markdown_report(back);
  EXPECT_NE(tables.find("Each part against the same part of the truth, mugs, full views: symmetric RMS, % of "
                        "the diagonal (truth_errors.hpp, own_part_rms_per_diagonal):\n\n| part | coupled |\n"
                        "|---|---|\n| body | 2.00 |\n| handle | 20.00 |\n| mean over parts | 11.00 |"),
            std::string::npos)
      << tables;
}

eval::EvalRow scene_row(const std::string& instance, int scene, eval::CutKind cut, double overlap,
                        double precision, double rms) {
  eval::EvalRow r = rms_row("holistic", scene, rms);
  r.instance = instance;
  r.scene = eval::SceneCutScore{cut, overlap, precision};
  return r;
}

TEST(EvalReport, DepthScenesRoundTripAndShowTheRightObjectShareAndTheRatioToTheHandCut) {
  using eval::CutKind;
  // Three scenes of mug_1: the scene cut took the whole mug in the first (overlap 0.9), a neighbour in the
  // second (overlap and precision 0), a piece of the mug in the third (overlap 0.4, every pixel the mug's:
  // the right object). One scene of mug_2 whose scene cut found nothing (NaN error): it counts as a scene, a
  // wrong choice, and leaves the means alone.
  std::vector<eval::EvalRow> rows = {rms_row("holistic", -1, 0.02),  // a full view, and a partial view 0
                                     rms_row("holistic", 0, 0.03),
                                     scene_row("mug_1", 0, CutKind::scene, 0.9, 0.95, 0.024),
                                     scene_row("mug_1", 0, CutKind::hand, 1.0, 1.0, 0.020),
                                     scene_row("mug_1", 1, CutKind::scene, 0.0, 0.0, 0.300),
                                     scene_row("mug_1", 1, CutKind::hand, 1.0, 1.0, 0.030),
                                     scene_row("mug_1", 2, CutKind::scene, 0.4, 1.0, 0.046),
                                     scene_row("mug_1", 2, CutKind::hand, 1.0, 1.0, 0.010),
                                     scene_row("mug_2", 0, CutKind::scene, 0.0, 0.0, std::nan("")),
                                     scene_row("mug_2", 0, CutKind::hand, 1.0, 1.0, 0.025)};
  testing::TempDir dir;
  eval::write_rows_csv(dir / "r.csv", rows);
  const std::vector<eval::EvalRow> back = eval::read_rows_csv(dir / "r.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_FALSE(back[0].scene);
  ASSERT_TRUE(back[2].scene);
  EXPECT_EQ(back[2].scene->cut, CutKind::scene);
  EXPECT_DOUBLE_EQ(back[2].scene->overlap, 0.9);
  EXPECT_DOUBLE_EQ(back[2].scene->precision, 0.95);
  EXPECT_EQ(back[3].scene->cut, CutKind::hand);
  EXPECT_TRUE(std::isnan(back[8].errors.symmetric_rms_per_diagonal));
  // The point-sampled views' tables leave the scene rows out (scene 0 is not partial view 0).
  EXPECT_DOUBLE_EQ(eval::mean_symmetric_rms_per_diagonal(back, "mugs", "holistic", false), 0.02);
  EXPECT_DOUBLE_EQ(eval::mean_symmetric_rms_per_diagonal(back, "mugs", "holistic", true), 0.03);
  // 4 scenes, 2 right; mean overlap (0.9 + 0 + 0.4 + 0) / 4 = 0.33; means over the three scenes both cuts
  // registered: (2.4 + 30 + 4.6) / 3 = 12.33 and (2.0 + 3.0 + 1.0) / 3 = 2.00 (% of the diagonal),
  // ratio 6.17.
  const std::string tables = eval::markdown_report(back);
  EXPECT_NE(tables.find("\nDepth scenes (eval --scenes): "), std::string::npos) << tables;
  EXPECT_NE(tables.find("| mugs | holistic | 4 | 2 (50%) | 0.33 | 12.33 | 2.00 | 6.17 |"), std::string::npos)
      << tables;
  // No scene rows, no table.
  EXPECT_EQ(eval::markdown_report({rows[0], rows[1]}).find("Depth scenes"), std::string::npos);
}

TEST(EvalReport, ACsvFromElsewhereIsRefusedWithItsName) {
  testing::TempDir dir;
  std::ofstream(dir / "other.csv") << "a,b,c\n1,2,3\n";
  try {
    eval::read_rows_csv(dir / "other.csv");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("other.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace partreg
