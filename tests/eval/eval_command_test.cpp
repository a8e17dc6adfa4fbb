// `partreg eval` end to end on a synthetic category (quick protocol), and its refusals of bad input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

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
  const Outcome result = run("eval " + data + " --protocol quick --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("registrations"), std::string::npos);  // the progress lines
  for (const char* file :
       {"results.csv", "tables.md", "run.json", "mugs_full_sweeps.png", "mugs_partial_sweeps.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "eval" / file)) << file;

  const std::vector<eval::EvalRow> rows = eval::read_rows_csv(dir / "eval" / "results.csv");
  // 2 tested instances x (1 full + 12 views + 3 observations x 4 kinds x 3 levels) x 3 variants.
  EXPECT_EQ(rows.size(), 2u * (13 + 36) * 3);
  for (const eval::EvalRow& row : rows) {
    ASSERT_TRUE(row.errors.correspondence_per_diagonal) << "synthetic data has ground-truth correspondences";
    ASSERT_TRUE(std::isfinite(row.errors.eq5_per_diagonal2));
    ASSERT_EQ(row.errors.part_eq5_per_diagonal2.size(), 2u);  // body, handle
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
