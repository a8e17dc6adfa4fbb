// Bad input as a user meets it: each reproducer through the real executables. Every case checks the exit
// code, one line naming the file or the option, no crash, and no output left behind.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

using testing::Outcome;

class Hardening : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::string path(const std::string& name) const { return (dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return path(name);
  }
  std::string cube() const {
    return write("cube.obj",
                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                 "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
                 "f 4 1 5\nf 4 5 8\n");
  }
  // Runs `arguments`; expects `code`, exactly one line of output starting "partreg: " and holding `words`,
  // and that the folder holds only `inputs` afterwards.
  void expect_failure(const std::string& arguments, int code, const std::string& words,
                      const std::vector<std::string>& inputs) {
    const Outcome result = testing::run_partreg(arguments);
    EXPECT_EQ(result.exit_code, code) << arguments << "\n" << result.output;
    const std::string last = result.output.substr(result.output.rfind("partreg: ") == std::string::npos
                                                      ? 0
                                                      : result.output.rfind("partreg: "));
    EXPECT_EQ(last.rfind("partreg: ", 0), 0u) << arguments << "\n" << result.output;
    EXPECT_NE(last.find(words), std::string::npos) << arguments << "\n" << result.output;
    EXPECT_EQ(std::count(last.begin(), last.end(), '\n'), 1) << "one line: " << result.output;
    EXPECT_EQ(result.output.find("[pcl"), std::string::npos) << "PCL spoke: " << result.output;
    EXPECT_EQ(result.output.find(".partial"), std::string::npos) << "a staging path: " << result.output;
    for (const std::string& name : dir.entries())
      EXPECT_NE(std::find(inputs.begin(), inputs.end(), name), inputs.end())
          << arguments << " left behind: " << name;
  }
};

TEST_F(Hardening, MalformedInputFilesFailWithExitOneAndTheFileNamed) {
  const std::string mesh = cube();
  const std::string tri =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\n";
  write("a.pcd", "0.1 0.2 0.3\n");
  write("huge.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n");
  write("noend.ply", tri + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  write("index.ply", tri + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  write("faces.off", "OFF\n3 1000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  // Passes partreg's header check but PCL's ascii reader finds too few values: PCL must stay silent.
  write("short.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\n"
                     "DATA ascii\n0 0 0\n" + std::string(40, ' ') + "\n");
  const std::vector<std::string> inputs = {"cube.obj", "a.pcd",     "huge.ply", "noend.ply",
                                           "index.ply", "faces.off", "short.pcd"};
  const std::string out = " --out " + path("o.ply");
  expect_failure("cpd " + path("a.pcd") + " " + mesh + out, 1, "a.pcd", inputs);
  expect_failure("cpd " + path("huge.ply") + " " + mesh + out, 1, "huge.ply", inputs);
  expect_failure("cpd " + path("short.pcd") + " " + mesh + out, 1, "short.pcd", inputs);
  expect_failure("label " + path("noend.ply") + " --part a --box 0,0,0,1,1,1 --out " + path("l.json"), 1,
                 "noend.ply", inputs);
  expect_failure("label " + path("index.ply") + " --part a --box 0,0,0,1,1,1 --out " + path("l.json"), 1,
                 "index.ply", inputs);
  expect_failure("render " + path("index.ply") + " --out " + path("r.png"), 1, "index.ply", inputs);
  expect_failure("views " + path("faces.off") + " --count 12 --out " + path("v"), 1, "faces.off", inputs);
  expect_failure("info " + path("a.pcd"), 1, "a.pcd", inputs);
}

TEST_F(Hardening, OutputNamesThatLieAreUsageErrorsBeforeAnyWork) {
  const std::string mesh = cube();
  const std::vector<std::string> inputs = {"cube.obj"};
  for (const char* name : {"p.npz", "p.txt", "p"})
    expect_failure("cpd " + mesh + " " + mesh + " --points 100 --out " + path(name), 2, name, inputs);
  expect_failure("cpd " + mesh + " " + mesh + " --points 100 --out " + path("p.ply") + " --json " + path("r.csv"), 2,
                 "r.csv", inputs);
  // Outputs are checked before the model is even read: nothing is written when the last one cannot be.
  expect_failure("register " + path("no.prm") + " " + mesh + " --points-out " + path("r.ply") + " --json " +
                     path("nodir/r.json"),
                 1, "nodir", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --mesh-out " + path("m.pcd"), 2, "m.pcd", inputs);
  expect_failure("render " + mesh + " --out " + path("r.jpg"), 2, "r.jpg", inputs);
  expect_failure("train " + path("nowhere") + " --out " + path("m.bin"), 2, "m.bin", inputs);
}

TEST_F(Hardening, EveryCloudFormatIsWhatItsNameSays) {
  const std::string mesh = cube();
  for (const char* name : {"p.ply", "p.pcd", "p.vtp", "p.xyz"}) {
    const Outcome result =
        testing::run_partreg("cpd " + mesh + " " + mesh + " --mode rigid --points 100 --out " + path(name));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    // Each reads back (the PCD through PCL, the .vtp through VTK) as a cloud of 100 points.
    const Outcome again = testing::run_partreg("cpd " + path(name) + " " + mesh + " --mode rigid --out " + path("q.ply"));
    EXPECT_EQ(again.exit_code, 0) << name << "\n" << again.output;
    EXPECT_NE(again.output.find("100 points"), std::string::npos) << name << "\n" << again.output;
  }
  std::ifstream pcd(dir / "p.pcd");
  std::string first;
  std::getline(pcd, first);
  EXPECT_EQ(first.rfind("# .PCD", 0), 0u) << first;
}

TEST_F(Hardening, DevicesFifosAndStdoutAreWrittenDirectly) {
  const std::string mesh = cube();
  const std::string common = "cpd " + mesh + " " + mesh + " --mode rigid --points 100 --out " + path("o.ply");
  // Run as root, this replaced the system's /dev/null with a regular file.
  Outcome result = testing::run_partreg(common + " --json /dev/null");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  struct stat status {};
  ASSERT_EQ(::stat("/dev/null", &status), 0);
  EXPECT_TRUE(S_ISCHR(status.st_mode));
  result = testing::run_partreg(common + " --json -");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("\"sigma2\""), std::string::npos) << result.output;
  const auto fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);
    received.assign(std::istreambuf_iterator<char>(in), {});
  });
  result = testing::run_partreg(common + " --json " + fifo.string());
  reader.join();
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(received.find("\"sigma2\""), std::string::npos) << received;
  ASSERT_EQ(::lstat(fifo.c_str(), &status), 0);
  EXPECT_TRUE(S_ISFIFO(status.st_mode)) << "the FIFO was replaced";
  // A full disk is an error naming the output, never an exit 0 with an empty file.
  if (std::filesystem::exists("/dev/full")) {
    result = testing::run_partreg(common + " --json /dev/full");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("cannot write /dev/full"), std::string::npos) << result.output;
  }
}

TEST_F(Hardening, AbsurdNumbersAreUsageErrorsNamingTheFlag) {
  const std::string mesh = cube();
  write("frames.json", R"({"format":"partreg-frames","version":1,"frames":[{"name":"g","position":[1e308,0,0],)"
                       R"("rotation":[[1,0,0],[0,1,0],[0,0,1]]}]})");
  write("labels.json", R"({"format":"partreg-labels","version":1,"source":"cube.obj","target":"faces",)"
                       R"("parts":[{"name":"a","color":[300,0,0]}],"count":12,"labels":[0,0,0,0,0,0,0,0,0,0,0,0]})");
  const std::vector<std::string> inputs = {"cube.obj", "frames.json", "labels.json"};
  const std::string out = " --out " + path("o.ply");
  expect_failure("cpd " + mesh + " " + mesh + " --points -5" + out, 2, "--points", inputs);
  expect_failure("cpd " + mesh + " " + mesh + " --max-iterations -1" + out, 2, "--max-iterations", inputs);
  expect_failure("synth mug --instances 100000000 --out " + path("s"), 2, "--instances", inputs);
  expect_failure("synth mug --instances -3 --out " + path("s"), 2, "--instances", inputs);
  expect_failure("render " + mesh + " --point-radius -1 --out " + path("r.png"), 2, "--point-radius", inputs);
  expect_failure("figure space " + path("no.prm") + " --size 100000x100000 --out " + path("f.png"), 2, "--size",
                 inputs);
  expect_failure("figure compare " + path("no.prm") + " " + mesh + " --restarts 0 --out " + path("f.png"), 2,
                 "--restarts", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --viewpoint nan,0,0", 2, "--viewpoint", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --samples -1", 2, "--samples", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --frames " + path("frames.json") +
                     " --frames-out " + path("g.json"),
                 1, "frames.json", inputs);
  expect_failure("label " + mesh + " --part b --in " + path("labels.json") + " --box 0,0,0,1,1,1 --out " +
                     path("l2.json"),
                 1, "labels.json", inputs);
  expect_failure("views " + mesh + " --count -2 --out " + path("v"), 2, "--count", inputs);
  expect_failure("train " + path("nowhere") + " --samples -10 --out " + path("m.prm"), 2, "--samples", inputs);
  expect_failure("train " + path("nowhere") + " --seam-band 2 --out " + path("m.prm"), 2, "--seam-band", inputs);
}

TEST_F(Hardening, AMissingSourceIsExitOneLikeEveryOtherMissingInput) {
  const std::string mesh = cube();
  expect_failure("cpd " + path("missing.ply") + " " + mesh + " --out " + path("o.ply"), 1, "missing.ply",
                 {"cube.obj"});
  expect_failure("cpd " + mesh + " " + path("missing.ply") + " --out " + path("o.ply"), 1, "missing.ply",
                 {"cube.obj"});
}

TEST_F(Hardening, SynthIsStagedAndAKilledRunsLeftoversAreCleaned) {
  pid_t dead = 0;
  for (pid_t pid = 4000000; pid > 1000 && dead == 0; --pid)
    if (::kill(pid, 0) != 0 && errno == ESRCH) dead = pid;
  ASSERT_NE(dead, 0);
  // What `synth` killed mid-run leaves: a hidden staging folder, never a half-filled `s` for train to use.
  const std::string stale = ".s.partial-" + std::to_string(dead);
  std::filesystem::create_directories(dir / stale / "mug_000");
  const Outcome result = testing::run_partreg("synth mug --instances 2 --correspondences 50 --out " + path("s"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "s" / "ground_truth" / "parameters.json"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"s"}) << "the killed run's staging folder is still there";
  EXPECT_EQ(result.output.find(".partial"), std::string::npos) << result.output;
}

#ifdef PARTREG_GUI_EXECUTABLE
TEST_F(Hardening, TheAppHasVersionAndUsageErrorsExitTwo) {
  auto run_gui = [](const std::string& arguments) {
    const std::string command = std::string(PARTREG_GUI_EXECUTABLE) + " " + arguments + " 2>&1";
    Outcome outcome;
    FILE* pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe)) outcome.output += buffer.data();
    const int status = pclose(pipe);
    outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return outcome;
  };
  Outcome version = run_gui("--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_NE(version.output.find("partreg-gui "), std::string::npos) << version.output;
  for (const char* bad : {"--frobnicate", "a b c", "--size 10x10 --headless", "--size 99999999x5 --headless"}) {
    const Outcome outcome = run_gui(bad);
    EXPECT_EQ(outcome.exit_code, 2) << bad << "\n" << outcome.output;
    EXPECT_NE(outcome.output.find("partreg-gui: "), std::string::npos) << bad << "\n" << outcome.output;
  }
  const Outcome missing = run_gui("--headless --script " + path("none.txt"));
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
}
#endif

// Numbers that passed the flags before and crashed, ran away or came out NaN: each is refused at once.
TEST_F(Hardening, NumbersOutsideTheirRangeAreRefusedWhereTheFlagIsDeclared) {
  const std::string mesh = cube();
  std::string huge;  // coordinates of 1e300: every moved point came out NaN with exit 0
  for (int i = 0; i < 60; ++i)
    huge += std::to_string(i % 3) + "e300 " + std::to_string(i % 5) + "e300 " + std::to_string(i) + "\n";
  write("huge.xyz", huge);
  const std::vector<std::string> inputs = {"cube.obj", "huge.xyz"};
  const std::string cpd = "cpd " + mesh + " " + mesh + " --mode nonrigid --points 50 --out " + path("o.ply");
  expect_failure(
      "cpd " + mesh + " " + path("huge.xyz") + " --mode nonrigid --points 50 --out " + path("o.ply"), 1,
      "coordinates beyond 1e12", inputs);
  expect_failure(cpd + " --beta inf", 2, "beta", inputs);
  expect_failure(cpd + " --beta 1e308", 2, "beta", inputs);
  expect_failure(cpd + " --lambda inf", 2, "lambda", inputs);
  expect_failure(cpd + " --tolerance inf", 2, "tolerance", inputs);
  expect_failure(cpd + " --seed -1", 2, "--seed", inputs);
  expect_failure("views " + mesh + " --count 12 --fov 1e-300 --out " + path("v"), 2, "--fov", inputs);
  for (const char* up : {"nan,0,1", "0,0,0", "0,1,0,junk"})
    expect_failure("render " + mesh + " --up " + up + " --out " + path("r.png"), 2, "--up", inputs);
  expect_failure("render " + mesh + " --point-radius nan --out " + path("r.png"), 2, "--point-radius",
                 inputs);
  expect_failure("eval " + path("nowhere") + " --folds -1 --out " + path("e"), 2, "--folds", inputs);
  expect_failure("eval " + path("nowhere") + " --samples -1 --out " + path("e"), 2, "--samples", inputs);
  expect_failure("eval " + path("nowhere") + " --seed -4 --out " + path("e"), 2, "--seed", inputs);
  expect_failure("eval " + path("nowhere") + " --shard 2/99999999999999999999 --out " + path("e"), 2,
                 "--shard", inputs);
  expect_failure("train " + path("nowhere") + " --samples 50000000 --out " + path("m.prm"), 2, "--samples",
                 inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --samples 50000000", 2, "--samples", inputs);
}

TEST_F(Hardening, TwoOutputsOfOneCommandMayNotBeTheSameFile) {
  const std::string mesh = cube();
  const std::vector<std::string> inputs = {"cube.obj"};
  const std::string cpd = "cpd " + mesh + " " + mesh + " --mode rigid --points 50";
  expect_failure(cpd + " --out - --json -", 2, "--out and --json name the same output", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --points-out " + path("same.ply") +
                     " --mesh-out " + path("same.ply"),
                 2, "--points-out and --mesh-out", inputs);
  expect_failure("register " + path("no.prm") + " " + mesh + " --frames " + mesh + " --frames-out " +
                     path("x.json") + " --json " + path("x.json"),
                 2, "--frames-out and --json", inputs);
}

// A control character in a file name is shown escaped: the error stays one line and cannot drive the
// terminal.
TEST_F(Hardening, ControlCharactersInNamesAreEscapedInMessages) {
  const Outcome result = testing::run_partreg("cpd '" + path("a\x1b[31mb\nc.ply") + "' '" + path("x.ply") +
                                              "' --out " + path("o.ply"));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("a\\x1b[31mb\\x0ac.ply"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find('\x1b'), std::string::npos) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
}

}  // namespace
}  // namespace partreg
