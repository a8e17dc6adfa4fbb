// The app's registration panel starts where `partreg register`, Python and the app's `register` verb start:
// every choice it offers reads its default from the library's settings, as the options table reports them.
#include <gtest/gtest.h>

#include <map>

#include "partreg/core/registration/registration_options.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/panels.hpp"

namespace partreg::ui {
namespace {

std::map<std::string, std::string> library_defaults() {
  std::map<std::string, std::string> values;
  for (const auto& [name, value] : core::registration_option_values(core::RegistrationSettings{}))
    values[name] = value;
  return values;
}

TEST(PanelDefaults, EveryRegistrationChoiceStartsAtTheLibrarysDefault) {
  const std::map<std::string, std::string> defaults = library_defaults();
  const AppState state{};
  const PanelState panel{};
  const auto offered = registration_panel_options(state, panel);
  ASSERT_EQ(offered.size(), 3u) << "variant, direction, loss";
  for (const auto& [name, value] : offered) {
    ASSERT_TRUE(defaults.count(name)) << name << " is not an option of the table";
    EXPECT_EQ(value, defaults.at(name)) << name;
  }
}

TEST(PanelDefaults, AChoiceMadeInThePanelIsWhatRegisterSends) {
  // A panel set to another direction sends it (so the comparison above can fail): observed is not the
  // default.
  ASSERT_NE(library_defaults().at("direction"), "observed");
  PanelState panel;
  panel.direction = enum_index(core::Direction::observed_to_canonical);
  panel.variant = enum_index(core::Variant::partwise);
  const std::map<std::string, std::string> sent = [&] {
    std::map<std::string, std::string> values;
    for (const auto& [name, value] : registration_panel_options(AppState{}, panel)) values[name] = value;
    return values;
  }();
  EXPECT_EQ(sent.at("direction"), "observed");
  EXPECT_EQ(sent.at("variant"), "partwise");
}

TEST(PanelDefaults, TheRegionToolsAreTheScriptsSelectionVerbs) {
  for (const char* verb : kRegionVerbs) {
    const Verb* found = find_verb(verb);
    ASSERT_NE(found, nullptr) << verb;
    EXPECT_FALSE(found->synopsis.empty()) << verb;
  }
}

}  // namespace
}  // namespace partreg::ui
