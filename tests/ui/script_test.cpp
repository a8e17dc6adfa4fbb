#include "partreg/ui/script.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"

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

}  // namespace
}  // namespace partreg::ui
