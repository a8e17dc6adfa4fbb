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
  // K (1 + P) steps: a CPD per instance but the canonical and per space, and a PCA-EM per space; one label CPD
  // and one held out to choose the seam weight per instance but the canonical.
  const std::size_t steps = instances * spaces + 2 * (instances - 1);
  std::size_t cpd_lines = 0, space_lines = 0, seam_lines = 0;
  for (const std::string& line : lines_of(train.err)) {
    if (line.find("] cpd ") != std::string::npos) {
      ++cpd_lines;
      // Each carries the count so far and the time left.
      EXPECT_EQ(line.rfind("[", 0), 0u) << line;
      EXPECT_NE(line.find("/" + std::to_string(steps) + " training steps"), std::string::npos) << line;
      EXPECT_NE(line.find(" left] "), std::string::npos) << line;
    }
    if (line.find("] space ") != std::string::npos) ++space_lines;
    if (line.find("] seam weight: held out") != std::string::npos) ++seam_lines;
    EXPECT_EQ(line.find('\r'), std::string::npos) << "a bar drawn into a log: " << line;
  }
  EXPECT_EQ(cpd_lines, (instances - 1) * (spaces + 1)) << train.err;
  EXPECT_EQ(space_lines, spaces) << train.err;
  EXPECT_EQ(seam_lines, instances - 1) << train.err;
  EXPECT_NE(train.err.find("coupled seam weight "), std::string::npos) << train.err;
  EXPECT_TRUE(summary["seam_weight"].is_number()) << summary.dump();
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

// Lines of `text` that hold `part`.
std::vector<std::string> lines_with(const std::string& text, const std::string& part) {
  std::vector<std::string> found;
  for (const std::string& line : lines_of(text))
    if (line.find(part) != std::string::npos) found.push_back(line);
  return found;
}

// A piped command's count lines ("k/n UNIT, m:ss elapsed, ~m:ss left"): a few, the last one the total, none
// with a bar's carriage return.
void expect_count_lines(const Streams& streams, std::size_t total, const std::string& unit) {
  EXPECT_EQ(streams.exit_code, 0) << streams.err;
  EXPECT_EQ(streams.err.find('\r'), std::string::npos) << "a bar drawn into a log: " << streams.err;
  const std::vector<std::string> counts =
      lines_with(streams.err, "/" + std::to_string(total) + " " + unit + ",");
  ASSERT_GE(counts.size(), 2u) << streams.err;
  EXPECT_LE(counts.size(), total) << streams.err;
  for (const std::string& line : counts) EXPECT_NE(line.find(" left"), std::string::npos) << line;
  EXPECT_NE(counts.back().find(std::to_string(total) + "/" + std::to_string(total)), std::string::npos)
      << counts.back();
}

TEST_F(Progress, PipedSynthAndViewsWriteCountLinesAndVerboseOnePerStep) {
  const Streams synth = run("synth mug --out " + path("mugs") + " --instances 20 --correspondences 50");
  expect_count_lines(synth, 20, "instances");
  EXPECT_TRUE(lines_with(synth.err, "made mug_").empty()) << "a detail line without --verbose: " << synth.err;
  const Streams synth_verbose =
      run("synth mug --out " + path("mugs_v") + " --instances 20 --correspondences 50 -v");
  EXPECT_EQ(lines_with(synth_verbose.err, "] made mug_").size(), 20u) << synth_verbose.err;

  const std::string mesh = path("mugs/mug_000/body.obj");
  const Streams views = run("views " + mesh + " --count 42 --out " + path("views"));
  expect_count_lines(views, 42, "views");
  const Streams views_verbose = run("views " + mesh + " --count 42 --out " + path("views_v") + " --verbose");
  EXPECT_EQ(lines_with(views_verbose.err, "] view_0").size(), 42u) << views_verbose.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "views_v/view_041.ply"));
}

TEST_F(Progress, QuietSynthViewsAndLabelWriteNothing) {
  const Streams synth = run("synth mug --out " + path("mugs") + " --instances 3 --quiet");
  EXPECT_EQ(synth.exit_code, 0);
  EXPECT_EQ(synth.err + synth.out, "");
  const std::string mesh = path("mugs/mug_000/body.obj");
  const Streams views = run("views " + mesh + " --count 12 --out " + path("views") + " -q");
  EXPECT_EQ(views.exit_code, 0);
  EXPECT_EQ(views.err + views.out, "");
  EXPECT_TRUE(std::filesystem::exists(dir / "views/views.json"));
  const std::string label = "label " + mesh + " --part top --plane 0,0,0,0,1,0 --out ";
  const Streams quiet_label = run(label + path("l.json") + " -q");
  EXPECT_EQ(quiet_label.exit_code, 0);
  EXPECT_EQ(quiet_label.err + quiet_label.out, "");
  const Streams normal_label = run(label + path("l2.json"));
  EXPECT_NE(normal_label.err.find("part top: "), std::string::npos) << normal_label.err;
  EXPECT_EQ(normal_label.err.find("the selector takes"), std::string::npos) << normal_label.err;
  const Streams verbose_label = run(label + path("l3.json") + " -v");
  EXPECT_NE(verbose_label.err.find("the selector takes"), std::string::npos) << verbose_label.err;
  // An error still shows under --quiet.
  const Streams missing = run("views " + path("nowhere.obj") + " --out " + path("v2") + " -q");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(lines_of(missing.err).size(), 1u) << missing.err;
}

#ifdef PARTREG_GUI_EXECUTABLE  // built with ui/: the render commands exist
TEST_F(Progress, PipedFiguresAndRenderWriteLinesAndQuietNothing) {
  make_mugs();
  ASSERT_EQ(run("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300 -q").exit_code, 0);
  const std::string observed = path("mugs/ground_truth/mug_003.ply");
  const std::string compare = "figure compare " + path("mug.prm") + " " + observed + " --size 80x60 --out ";
  // Two variants: a registration each (its line), then four panels (counts).
  const Streams figure = run(compare + path("c.png"));
  EXPECT_EQ(lines_with(figure.err, "] holistic: mean fit ").size(), 1u) << figure.err;
  EXPECT_EQ(lines_with(figure.err, "] hol+part: mean fit ").size(), 1u) << figure.err;
  expect_count_lines(figure, 6, "steps");
  const Streams quiet_figure = run(compare + path("c2.png") + " --quiet");
  EXPECT_EQ(quiet_figure.exit_code, 0);
  EXPECT_EQ(quiet_figure.err + quiet_figure.out, "");
  EXPECT_TRUE(std::filesystem::exists(dir / "c2.png"));

  // The handle's space: a row per principal direction, five shapes each.
  const std::string space = "figure space " + path("mug.prm") + " --space handle --size 48x36 --out ";
  const Streams walk = run(space + path("s.png"));
  ASSERT_EQ(walk.exit_code, 0) << walk.err;
  const std::vector<std::string> rows = lines_with(walk.err, " principal directions");
  ASSERT_EQ(rows.size(), 1u) << walk.err;
  const std::size_t panels = 5 * std::stoul(rows[0].substr(rows[0].find(": ") + 2));
  expect_count_lines(walk, panels, "panels");
  EXPECT_EQ(run(space + path("s2.png") + " -q").err, "");

  const std::string render =
      "render " + observed + " " + path("mugs/mug_000/body.obj") + " --size 64x48 --out ";
  const Streams drawn = run(render + path("r.png"));
  EXPECT_EQ(drawn.exit_code, 0) << drawn.err;
  EXPECT_EQ(lines_with(drawn.err, "[1/3 steps, ").size(), 1u) << drawn.err;
  EXPECT_EQ(lines_with(drawn.err, "] read ").size(), 2u) << drawn.err;
  EXPECT_EQ(lines_with(drawn.err, "[3/3 steps, ").size(), 1u) << drawn.err;
  EXPECT_EQ(drawn.err.find('\r'), std::string::npos) << drawn.err;
  EXPECT_EQ(drawn.err.find("camera at "), std::string::npos) << "a detail line without --verbose";
  EXPECT_NE(run(render + path("r3.png") + " -v").err.find("camera at "), std::string::npos);
  const Streams quiet_render = run(render + path("r2.png") + " -q");
  EXPECT_EQ(quiet_render.exit_code, 0);
  EXPECT_EQ(quiet_render.err + quiet_render.out, "");
}
#endif

TEST_F(Progress, EveryCommandTakesQuietAndVerbose) {
  std::vector<std::string> commands = {"cpd",      "train", "info", "synth", "label",
                                       "register", "views", "eval", "report"};
#ifdef PARTREG_GUI_EXECUTABLE  // built with ui/: the render commands exist too
  commands.insert(commands.end(), {"render", "figure", "figure compare", "figure space"});
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
