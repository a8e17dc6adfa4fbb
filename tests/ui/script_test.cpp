#include "partreg/ui/script.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/ui/executor.hpp"

namespace partreg::ui {
namespace {

TEST(Script, ParsesVerbsArgumentsOptionsAndComments) {
  const std::vector<Command> commands = parse_script(
      "# a comment line\n"
      "\n"
      "load \"my mugs/mug 1.obj\"   # trailing comment\n"
      "paint 128 140 radius=6\n"
      "set_latent handle 1 +2.0\n");
  ASSERT_EQ(commands.size(), 3u);
  EXPECT_EQ(commands[0].verb, "load");
  EXPECT_EQ(commands[0].arguments, std::vector<std::string>{"my mugs/mug 1.obj"});
  EXPECT_EQ(commands[0].line, 3);
  EXPECT_EQ(commands[1].arguments, (std::vector<std::string>{"128", "140"}));
  EXPECT_EQ(commands[1].option("radius"), "6");
  EXPECT_EQ(commands[1].option("missing", "x"), "x");
  EXPECT_EQ(commands[2].arguments[2], "+2.0");
}

TEST(Script, TextFormRoundTrips) {
  const Command command = make_command("load", {"a b.obj"});
  EXPECT_EQ(command.to_string(), "load \"a b.obj\"");
  const std::vector<Command> again = parse_script(command.to_string() + "\npaint 1 2 radius=3");
  EXPECT_EQ(again[0].arguments[0], "a b.obj");
  EXPECT_EQ(again[1].to_string(), "paint 1 2 radius=3");
}

TEST(Script, NamesTheLineOfAnUnknownVerb) {
  try {
    parse_script("load a.obj\nfly away\n");
    FAIL() << "an unknown verb must be refused";
  } catch (const UsageError& error) {
    EXPECT_NE(std::string(error.what()).find("line 2"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("fly"), std::string::npos) << error.what();
  }
}

TEST(Script, RefusesWrongArgumentCountsOptionsAndQuotes) {
  EXPECT_THROW(parse_script("paint 12"), UsageError);
  EXPECT_THROW(parse_script("quit now"), UsageError);
  EXPECT_THROW(parse_script("paint 1 2 size=3"), UsageError);
  EXPECT_THROW(parse_script("load \"unterminated"), UsageError);
  EXPECT_NO_THROW(parse_script("step -3\ngoto_step last\ncamera front"));
}

TEST(Script, MissingFileIsAnInputError) { EXPECT_THROW(read_script("/nonexistent/script.txt"), InputError); }

TEST(Script, EveryVerbHasASynopsis) {
  EXPECT_GE(command_synopses().size(), 30u);
  for (const auto& [verb, synopsis] : command_synopses()) EXPECT_FALSE(verb.empty());
}

// docs/gui.md's table of commands names every verb of the registry, and only those.
TEST(Script, TheDocsTableListsExactlyTheRegisteredVerbs) {
  std::ifstream file(std::string(PARTREG_SOURCE_DIR) + "/docs/gui.md");
  ASSERT_TRUE(file) << "docs/gui.md not found";
  std::set<std::string> documented;
  const std::regex verb_in_cell(R"(`([a-z_]+)[ `])");
  for (std::string line; std::getline(file, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(0, line.find(" | ", 2));
    for (std::sregex_iterator it(first_cell.begin(), first_cell.end(), verb_in_cell), end; it != end; ++it)
      documented.insert((*it)[1]);
  }
  std::set<std::string> registered;
  for (const Verb& verb : verbs()) registered.insert(verb.name);
  EXPECT_EQ(documented, registered);
}

// The register verb accepts every registration setting by its option name, and the variant as its argument.
TEST(Script, RegisterTakesEveryRegistrationSetting) {
  const Verb* registration = find_verb("register");
  ASSERT_NE(registration, nullptr);
  for (const core::RegistrationOption& option : core::registration_options()) {
    const bool accepted = std::find(registration->options.begin(), registration->options.end(),
                                    option.name) != registration->options.end();
    EXPECT_EQ(accepted, option.name != "variant") << option.name;
  }
}

// The train verb accepts every training setting by its option name, and where the model goes.
TEST(Script, TrainTakesEveryTrainingSetting) {
  const Verb* train = find_verb("train");
  ASSERT_NE(train, nullptr);
  std::set<std::string> expected{"out"};
  for (const core::TrainingOption& option : core::training_options()) expected.insert(option.name);
  EXPECT_EQ(std::set<std::string>(train->options.begin(), train->options.end()), expected);
}

}  // namespace
}  // namespace partreg::ui
