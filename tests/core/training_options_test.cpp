// The training options (core/training/training_options.hpp): one table that `partreg train`, `partreg eval`
// and Python's train() read, whose ranges train_category checks too.
#include "partreg/core/training/training_options.hpp"

#include <gtest/gtest.h>

#include <set>

#include "partreg/core/errors.hpp"
#include "support/option_tables.hpp"

namespace partreg::core {
namespace {

using testing::usage_message;

TEST(TrainingOptions, EveryOptionRoundTripsItsDefaultAndAChangedValue) {
  const TrainingSettings defaults;
  for (const TrainingOption& option : training_options()) {
    TrainingSettings settings;
    option.set(settings, option.get(defaults));
    EXPECT_EQ(option.get(settings), option.get(defaults)) << option.name;
  }
  TrainingSettings settings;
  training_option("seam-band").set(settings, "0.12");
  training_option("points").set(settings, "800");
  training_option("part-points").set(settings, "0");
  training_option("lambda").set(settings, "2.5");
  training_option("up").set(settings, "0,0,1");
  training_option("seam-weights").set(settings, "0.5,20");
  EXPECT_EQ(settings.seam_weight_candidates, (std::vector<double>{0.5, 20.0}));
  EXPECT_EQ(training_option("seam-weights").get(settings), "0.5,20");
  EXPECT_DOUBLE_EQ(settings.seam_band, 0.12);
  EXPECT_EQ(settings.canonical_points, 800);
  EXPECT_EQ(settings.min_part_points, 0);
  EXPECT_DOUBLE_EQ(settings.lambda, 2.5);
  EXPECT_EQ(settings.up, Eigen::Vector3d(0, 0, 1));
  // What an evaluation records reads back into the same settings.
  TrainingSettings copy;
  for (const auto& [name, value] : training_option_values(settings)) training_option(name).set(copy, value);
  EXPECT_EQ(training_option_values(copy), training_option_values(settings));
}

TEST(TrainingOptions, BadValuesAreRefusedNamingTheValue) {
  TrainingSettings settings;
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"seam-band", "2"},     {"seam-band", "-0.1"},    {"latent", "0"},        {"points", "9"},
      {"beta", "0"},          {"lambda", "nan"},        {"up", "0,0,0"},        {"part-points", "1.5"},
      {"seam-weights", ""},   {"seam-weights", "1,,3"}, {"seam-weights", "1,"}, {"seam-weights", "-1"},
      {"seam-weights", "1,x"}};
  for (const auto& pair : bad) {
    const std::string& name = pair.first;
    const std::string& value = pair.second;
    const std::string message = usage_message([&] { training_option(name).set(settings, value); });
    EXPECT_NE(message.find(name), std::string::npos) << name << "=" << value << ": '" << message << "'";
  }
  EXPECT_NE(usage_message([] { training_option("seam_band"); }).find("unknown training setting"), std::string::npos);
  EXPECT_EQ(training_option_values(settings), training_option_values(TrainingSettings{}));  // unchanged
}

TEST(TrainingOptions, ValidateAndTrainingRefuseSettingsBuiltInCode) {
  TrainingSettings settings;
  EXPECT_NO_THROW(validate(settings));
  settings.seam_band = 1.5;
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.up = Eigen::Vector3d(0, std::nan(""), 1);
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.seam_weight_candidates = {};
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.latent_dimensions = 0;
  const TrainingInstance a{"a", Points::Random(50, 3), {}, {}, {}}, b{"b", Points::Random(50, 3), {}, {}, {}};
  EXPECT_THROW(train_category("c", {a, b}, {}, settings), UsageError);
}

// docs/training.md's table of settings lists exactly the declared options.
TEST(TrainingOptions, TheDocsTableListsEveryOption) {
  const std::set<std::string> documented = testing::documented_options("training.md");
  ASSERT_FALSE(documented.empty()) << "no table of settings in docs/training.md";
  std::set<std::string> declared;
  for (const TrainingOption& option : training_options()) declared.insert(option.name);
  EXPECT_EQ(documented, declared);
}

}  // namespace
}  // namespace partreg::core
