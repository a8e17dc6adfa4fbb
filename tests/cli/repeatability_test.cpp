// Same input, same output: `cpd`, `train`, `register` and `eval` write the same bytes with one thread and with
// two (the parallel sums run over fixed pieces in a fixed order), times aside.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

std::string contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A result JSON without its wall-clock times ("seconds", "stage_seconds", ...): everything else must agree.
nlohmann::json without_times(nlohmann::json value) {
  if (value.is_object()) {
    nlohmann::json kept = nlohmann::json::object();
    for (auto& [key, item] : value.items()) {
      if (key.find("seconds") == std::string::npos) kept[key] = without_times(item);
    }
    return kept;
  }
  if (value.is_array()) {
    for (auto& item : value) item = without_times(item);
  }
  return value;
}

nlohmann::json json_without_times(const std::filesystem::path& path) {
  return without_times(nlohmann::json::parse(contents(path)));
}

// results.csv without its time columns (headers naming seconds).
std::vector<std::vector<std::string>> csv_without_times(const std::filesystem::path& path) {
  std::istringstream text(contents(path));
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> keep;
  for (std::string line; std::getline(text, line);) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    if (keep.empty()) {
      for (const std::string& header : cells) keep.push_back(header.find("seconds") == std::string::npos);
    }
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i >= keep.size() || keep[i]) kept.push_back(cells[i]);
    }
    rows.push_back(kept);
  }
  return rows;
}

class Repeatability : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder = new testing::TempDir;
    run("synth mug --instances 3 --seed 5 --out " + path("mugs"));
  }
  static void TearDownTestSuite() {
    delete folder;
    folder = nullptr;
  }
  static std::string path(const std::string& name) { return (*folder / name).string(); }
  static void run(const std::string& arguments) {
    const testing::Outcome outcome = testing::run_partreg(arguments + " -q");
    ASSERT_EQ(outcome.exit_code, 0) << arguments << "\n" << outcome.output;
  }
  // `command` once with --threads 1 and once with 2, "{out}" in it replaced by the run's own output prefix.
  static void run_with_one_and_two_threads(const std::string& command) {
    for (const char* threads : {"1", "2"}) {
      std::string arguments = command;
      for (std::size_t at; (at = arguments.find("{out}")) != std::string::npos;) {
        arguments.replace(at, 5, path(std::string("threads") + threads));
      }
      run(arguments + " --threads " + threads);
    }
  }
  static inline testing::TempDir* folder = nullptr;
};

TEST_F(Repeatability, CpdWritesTheSameBytesOnOneThreadAndOnTwo) {
  const std::string source = path("mugs/mug_000/body.obj"), target = path("mugs/mug_001/body.obj");
  for (const char* mode : {"rigid", "nonrigid"}) {
    run_with_one_and_two_threads(std::string("cpd ") + source + " " + target + " --mode " + mode +
                                 " --points 800 --out {out}_cpd.ply --json {out}_cpd.json");
    EXPECT_EQ(contents(path("threads1_cpd.ply")), contents(path("threads2_cpd.ply"))) << mode;
    EXPECT_EQ(json_without_times(path("threads1_cpd.json")), json_without_times(path("threads2_cpd.json")))
        << mode;
  }
}

TEST_F(Repeatability, TrainAndRegisterWriteTheSameBytesOnOneThreadAndOnTwo) {
  run_with_one_and_two_threads("train " + path("mugs") + " --hold-out mug_002 --points 400 --out {out}.prm");
  const std::string model = contents(path("threads1.prm"));
  ASSERT_FALSE(model.empty());
  EXPECT_EQ(model, contents(path("threads2.prm")));

  // The held-out instance's ground-truth points (2000, its surface) as the observation.
  run_with_one_and_two_threads("register " + path("threads1.prm") + " " + path("mugs/ground_truth/mug_002.ply") +
                               " --points-out {out}_points.ply --mesh-out {out}_mesh.obj --json {out}_register.json");
  EXPECT_EQ(contents(path("threads1_points.ply")), contents(path("threads2_points.ply")));
  EXPECT_EQ(contents(path("threads1_mesh.obj")), contents(path("threads2_mesh.obj")));
  EXPECT_EQ(json_without_times(path("threads1_register.json")), json_without_times(path("threads2_register.json")));
}

TEST_F(Repeatability, EvalWritesTheSameRowsOnOneThreadAndOnTwo) {
  run_with_one_and_two_threads("eval " + path("mugs") +
                               " --protocol quick --variants holistic --views 0 --sweeps none --points 300 "
                               "--samples 1000 --out {out}_eval");
  const auto rows = csv_without_times(path("threads1_eval/results.csv"));
  ASSERT_GT(rows.size(), 3u);  // a header and a row per held-out instance
  EXPECT_EQ(rows, csv_without_times(path("threads2_eval/results.csv")));
}

}  // namespace
}  // namespace partreg
