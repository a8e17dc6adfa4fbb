// Progress and verbosity of the real `partreg` executable: lines in a log (stderr not a terminal), --quiet
// and --verbose on every command.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_dir.hpp"

namespace partreg {
namespace {

// One run with stdout and stderr kept apart (both files: neither is a terminal).
struct Streams {
  int exit_code = -1;
  std::string out, err;
};

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class Progress : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::string path(const std::string& name) const { return (dir / name).string(); }
  Streams run(const std::string& arguments) const {
    const std::string command = std::string(PARTREG_EXECUTABLE) + " " + arguments + " >" +
                                path("stdout.txt") + " 2>" + path("stderr.txt") + " </dev/null";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(dir / "stdout.txt"),
            read_text(dir / "stderr.txt")};
  }
  // A small synthetic category with parts: 4 instances, so 3 CPDs per space.
  void make_mugs() const {
    const Streams synth = run("synth mug --out " + path("mugs") + " --instances 4 --seed 2");
    ASSERT_EQ(synth.exit_code, 0) << synth.err;
  }
};

TEST_F(Progress, PipedTrainWritesOneLinePerCpd) {
  make_mugs();
  const Streams train =
      run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300 --json " + path("t.json"));
  ASSERT_EQ(train.exit_code, 0) << train.err;
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "t.json"));
  const std::size_t instances = summary["instances"].size(), spaces = summary["spaces"].size();
  ASSERT_EQ(instances, 4u);
  ASSERT_EQ(spaces, 3u);  // holistic, body, handle
  // K (1 + P) steps: a CPD per instance but the canonical and per space, and a PCA-EM per space.
  const std::size_t steps = instances * spaces;
  std::size_t cpd_lines = 0, space_lines = 0;
  for (const std::string& line : lines_of(train.err)) {
    if (line.find("] cpd ") != std::string::npos) {
      ++cpd_lines;
      // Each carries the count so far and the time left.
      EXPECT_EQ(line.rfind("[", 0), 0u) << line;
      EXPECT_NE(line.find("/" + std::to_string(steps) + " training steps"), std::string::npos) << line;
      EXPECT_NE(line.find(" left] "), std::string::npos) << line;
    }
    if (line.find("] space ") != std::string::npos) ++space_lines;
    EXPECT_EQ(line.find('\r'), std::string::npos) << "a bar drawn into a log: " << line;
  }
  EXPECT_EQ(cpd_lines, (instances - 1) * spaces) << train.err;
  EXPECT_EQ(space_lines, spaces) << train.err;
}

TEST_F(Progress, QuietPrintsNothingButAnError) {
  make_mugs();
  const Streams train = run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300 --quiet");
  EXPECT_EQ(train.exit_code, 0) << train.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "mug.prm"));
  EXPECT_EQ(train.err, "");
  EXPECT_EQ(train.out, "");
  const Streams normal = run("train " + path("mugs") + " --out " + path("mug2.prm") + " --points 300");
  EXPECT_NE(normal.err, "");  // without --quiet the same run does talk: the check above can fail

  const Streams cpd = run("cpd " + path("mugs/ground_truth/mug_000.ply") + " " +
                          path("mugs/ground_truth/mug_001.ply") + " --out " + path("moved.ply") + " -q");
  EXPECT_EQ(cpd.exit_code, 0) << cpd.err;
  EXPECT_EQ(cpd.err + cpd.out, "");

  // Errors still show, as one line, with their exit code: a runtime failure (1) and a usage error (2).
  const Streams missing = run("train " + path("nowhere") + " --out " + path("x.prm") + " --quiet");
  EXPECT_EQ(missing.exit_code, 1);
  ASSERT_EQ(lines_of(missing.err).size(), 1u) << missing.err;
  EXPECT_EQ(missing.err.rfind("partreg: ", 0), 0u) << missing.err;
  EXPECT_EQ(missing.out, "");
  const Streams usage = run("eval " + path("mugs") + " --out " + path("e") + " --shard 3/2 --quiet");
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(lines_of(usage.err).size(), 1u) << usage.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.prm"));
  // --quiet and --verbose together are a usage error.
  EXPECT_EQ(run("info " + path("mug.prm") + " --quiet --verbose").exit_code, 2);
}

TEST_F(Progress, VerboseCpdLogsEveryIteration) {
  make_mugs();
  const std::string pair =
      path("mugs/ground_truth/mug_000.ply") + " " + path("mugs/ground_truth/mug_001.ply");
  const Streams verbose =
      run("cpd " + pair + " --out " + path("a.ply") + " --json " + path("a.json") + " -v");
  ASSERT_EQ(verbose.exit_code, 0) << verbose.err;
  const int iterations = nlohmann::json::parse(read_text(dir / "a.json"))["iterations"];
  int iteration_lines = 0;
  for (const std::string& line : lines_of(verbose.err))
    if (line.find("] iteration ") != std::string::npos) {
      ++iteration_lines;
      EXPECT_NE(line.find("at most"), std::string::npos) << line;  // the cap bounds the time left
    }
  EXPECT_EQ(iteration_lines, iterations) << verbose.err;
  const Streams normal = run("cpd " + pair + " --out " + path("b.ply"));
  ASSERT_EQ(normal.exit_code, 0) << normal.err;
  EXPECT_EQ(normal.err.find("iteration 1:"), std::string::npos) << normal.err;
}

TEST_F(Progress, EveryCommandTakesQuietAndVerbose) {
  std::vector<std::string> commands = {"cpd",      "train", "info", "synth", "label",
                                       "register", "views", "eval", "report"};
#ifdef PARTREG_GUI_EXECUTABLE  // built with ui/: the render commands exist too
  commands.insert(commands.end(), {"render", "figure"});
#endif
  for (const std::string& command : commands) {
    const Streams help = run(command + " --help");
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_NE(help.out.find("--quiet"), std::string::npos) << command;
    EXPECT_NE(help.out.find("--verbose"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace partreg
