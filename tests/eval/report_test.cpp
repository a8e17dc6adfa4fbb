// Errors on hand-made sets, and the CSV and tables the evaluation writes.
#include "partreg/eval/report.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/truth_errors.hpp"
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
