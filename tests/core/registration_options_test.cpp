#include "partreg/core/registration/registration_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "partreg/core/errors.hpp"
#include "support/option_tables.hpp"

namespace partreg::core {
namespace {

using testing::usage_message;

TEST(EnumNames, ParsePrintAndListOneTable) {
  EXPECT_EQ(parse_enum<Variant>("hol+part"), Variant::hol_part);
  EXPECT_EQ(parse_enum<Variant>("coupled"), Variant::coupled);
  EXPECT_EQ(enum_name(Direction::canonical_to_observed), "canonical");
  EXPECT_EQ(enum_choices<Loss>(), "squared | huber | cauchy | trimmed");
  for (const std::string& name : enum_names<Variant>()) EXPECT_EQ(enum_name(parse_enum<Variant>(name)), name);
  const std::string message = usage_message([] { parse_enum<Variant>("wholistic"); });
  EXPECT_NE(message.find("unknown variant 'wholistic'"), std::string::npos) << message;
  EXPECT_NE(message.find("holistic, partwise, hol+part"), std::string::npos) << message;
}

TEST(RegistrationOptions, EveryOptionRoundTripsItsDefaultAndAChangedValue) {
  const RegistrationSettings defaults;
  for (const RegistrationOption& option : registration_options()) {
    RegistrationSettings settings;
    option.set(settings, option.get(defaults));
    EXPECT_EQ(option.get(settings), option.get(defaults)) << option.name;
  }
  RegistrationSettings settings;
  set_registration_option(settings, "direction", "canonical");
  set_registration_option(settings, "loss-scale", "0.035");
  set_registration_option(settings, "restarts", "6");
  set_registration_option(settings, "scale", "true");
  set_registration_option(settings, "up", "0,0,2");
  set_registration_option(settings, "viewpoint", "1,2,3");
  set_registration_option(settings, "iterations", "9");
  set_registration_option(settings, "observed-points", "500");
  EXPECT_EQ(settings.objective.direction, Direction::canonical_to_observed);
  EXPECT_DOUBLE_EQ(settings.objective.loss_scale, 0.035);
  EXPECT_EQ(settings.initialisation.restarts, 6);
  EXPECT_TRUE(settings.objective.estimate_scale);
  EXPECT_EQ(settings.initialisation.up, std::optional<Eigen::Vector3d>(Eigen::Vector3d(0, 0, 2)));
  ASSERT_TRUE(settings.viewpoint);
  EXPECT_EQ(*settings.viewpoint, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(settings.convergence.outer_iterations, 9);
  EXPECT_EQ(settings.sampling.observed_points, 500);
  set_registration_option(settings, "viewpoint", "none");
  EXPECT_FALSE(settings.viewpoint);
  // Unset, the up axis is the model's own (train --up), and says so.
  EXPECT_EQ(registration_option("up").get(RegistrationSettings{}), "model");
  set_registration_option(settings, "up", "model");
  EXPECT_FALSE(settings.initialisation.up);
  // So is the coupled seam weight (the one training chose for the category).
  EXPECT_EQ(registration_option("seam-weight").get(RegistrationSettings{}), "model");
  set_registration_option(settings, "seam-weight", "3");
  EXPECT_EQ(settings.objective.seam_weight, std::optional<double>(3.0));
  // The values a result file records read back into the same request.
  RegistrationSettings copy;
  for (const auto& [name, value] : registration_option_values(settings))
    set_registration_option(copy, name, value);
  EXPECT_EQ(registration_option_values(copy), registration_option_values(settings));
}

TEST(RegistrationOptions, BadValuesNameTheValueNotAFlag) {
  RegistrationSettings settings;
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"restarts", "0"},     {"restarts", "2.5"},     {"restarts", "-3"},       {"screening-points", "-1"},
      {"loss-scale", "nan"}, {"up", "0,0,0"},         {"viewpoint", "nan,0,0"}, {"trim", "1.5"},
      {"loss", "l1"},        {"iterations", "many"},  {"scale", "maybe"},       {"observed-points", "1e30"},
      {"seam-weight", "-1"}, {"seam-weight", "stiff"}};
  for (const auto& pair : bad) {
    const std::string& name = pair.first;
    const std::string& value = pair.second;
    const std::string message = usage_message([&] { set_registration_option(settings, name, value); });
    EXPECT_FALSE(message.empty()) << name << "=" << value << " was accepted";
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
  }
  EXPECT_FALSE(usage_message([&] { set_registration_option(settings, "restart", "2"); }).empty());
  EXPECT_EQ(settings.initialisation.restarts, RegistrationSettings{}.initialisation.restarts);  // unchanged
}

TEST(RegistrationOptions, ValidateRefusesSettingsBuiltInCode) {
  RegistrationSettings settings;
  EXPECT_NO_THROW(validate(settings));
  settings.initialisation.restarts = 0;
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.initialisation.up = Eigen::Vector3d::Zero();
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.objective.loss_scale = -1.0;
  EXPECT_THROW(validate(settings), UsageError);
  settings = {};
  settings.objective.seam_weight = std::nan("");
  EXPECT_THROW(validate(settings), UsageError);
}

// docs/registration.md's table of settings lists exactly the declared options.
TEST(RegistrationOptions, TheDocsTableListsEveryOption) {
  const std::set<std::string> documented = testing::documented_options("registration.md");
  ASSERT_FALSE(documented.empty()) << "no table of settings in docs/registration.md";
  std::set<std::string> declared;
  for (const RegistrationOption& option : registration_options()) declared.insert(option.name);
  EXPECT_EQ(documented, declared);
}

}  // namespace
}  // namespace partreg::core
