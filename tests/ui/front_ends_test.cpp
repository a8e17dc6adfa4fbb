// The same registration settings reach the core through every front end: `partreg register`, `partreg eval`
// and the app's `register` verb take the same names and give the same request (and, on one observation, the
// same result).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/core/registration/registration_options.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/script.hpp"
#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"
#include "ui_fixtures.hpp"

namespace partreg::ui {
namespace {

// Settings far from the defaults, so that a front end dropping one would be seen.
const std::vector<std::pair<std::string, std::string>> kSettings = {
    {"direction", "canonical"}, {"loss", "cauchy"},     {"loss-scale", "0.03"},
    {"prior-weight", "0.001"},  {"restarts", "2"},      {"iterations", "7"},
    {"inner-iterations", "3"},  {"tolerance", "1e-06"}, {"observed-points", "1500"}};

std::string as_flags() {
  std::string flags;
  for (const auto& [name, value] : kSettings) flags += " --" + name + " " + value;
  return flags;
}

std::string as_script_options() {
  std::string options;
  for (const auto& [name, value] : kSettings) options += " " + name + "=" + value;
  return options;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  return nlohmann::json::parse(std::ifstream(path));
}

TEST(FrontEnds, RegisterEvalAndTheAppTakeTheSameSettings) {
  const testing::TempDir dir;
  const std::string model = testing::small_model_path().string(),
                    observed = testing::observed_cloud_path().string();
  const testing::Outcome cli =
      testing::run_partreg("register " + model + " " + observed + " --variant holistic" + as_flags() +
                           " --json " + (dir / "cli.json").string());
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  const nlohmann::json cli_result = read_json(dir / "cli.json");

  AppState state;
  for (const Command& command :
       parse_script("load " + model + "\nload " + observed + "\nregister holistic" + as_script_options()))
    execute(state, command);
  ASSERT_TRUE(state.registration.result);
  nlohmann::json app_settings = nlohmann::json::object();
  for (const auto& [name, value] : core::registration_option_values(state.registration.settings))
    app_settings[name] = value;
  EXPECT_EQ(app_settings, cli_result["settings"]);
  for (const auto& [name, value] : kSettings) EXPECT_EQ(app_settings[name], value) << name;
  // One observation, one request: one result.
  const core::SpaceFit& fit = state.registration.result->fits.at(0);
  const nlohmann::json& cli_latent = cli_result["spaces"][0]["latent"];
  ASSERT_EQ(cli_latent.size(), static_cast<std::size_t>(fit.latent.size()));
  for (Eigen::Index k = 0; k < fit.latent.size(); ++k)
    EXPECT_NEAR(cli_latent[static_cast<std::size_t>(k)].get<double>(), fit.latent[k], 1e-12);

  const std::filesystem::path dataset = testing::mug_dataset("front_ends_mugs", 3);
  const testing::Outcome eval = testing::run_partreg(
      "eval " + dataset.string() + " --protocol quick --views 0 --levels 1 --variants holistic" + as_flags() +
      " --out " + (dir / "eval").string());
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  nlohmann::json expected = cli_result["settings"];
  expected.erase("variant");
  expected.erase("viewpoint");  // each of eval's views brings its own camera
  EXPECT_EQ(read_json(dir / "eval" / "run.json")["registration"], expected);
}

TEST(FrontEnds, ABadValueIsRefusedAlikeEverywhere) {
  const testing::TempDir dir;
  const std::string model = testing::small_model_path().string(),
                    observed = testing::observed_cloud_path().string();
  const testing::Outcome cli = testing::run_partreg("register " + model + " " + observed + " --restarts 0");
  EXPECT_EQ(cli.exit_code, 2) << cli.output;
  EXPECT_NE(cli.output.find("--restarts: restarts must be in [1, 360], not 0"), std::string::npos)
      << cli.output;
  AppState state;
  for (const Command& command : parse_script("load " + model + "\nload " + observed)) execute(state, command);
  Command command;
  ASSERT_TRUE(parse_command("register holistic restarts=0", 1, command));
  EXPECT_FALSE(execute_reporting(state, command));
  EXPECT_NE(state.status.find("restarts must be in [1, 360], not 0"), std::string::npos) << state.status;
  EXPECT_THROW(parse_command("register holistic restart=2", 1, command), UsageError);  // not a setting
}

}  // namespace
}  // namespace partreg::ui
