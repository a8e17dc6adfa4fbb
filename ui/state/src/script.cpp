#include "partreg/ui/script.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"
#include "partreg/ui/executor.hpp"

namespace partreg::ui {
namespace {

[[noreturn]] void fail(int line_number, const std::string& what) {
  throw UsageError((line_number > 0 ? "line " + std::to_string(line_number) + ": " : std::string()) + what);
}

std::vector<std::string> tokenize(const std::string& line, int line_number) {
  std::vector<std::string> tokens;
  std::string current;
  bool in_token = false, quoted = false;
  for (const char c : line) {
    if (quoted) {
      if (c == '"')
        quoted = false;
      else
        current += c;
    } else if (c == '"') {
      quoted = in_token = true;
    } else if (c == '#') {
      break;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      if (in_token) tokens.push_back(current);
      current.clear();
      in_token = false;
    } else {
      current += c;
      in_token = true;
    }
  }
  if (quoted) fail(line_number, "unterminated quote");
  if (in_token) tokens.push_back(current);
  return tokens;
}

}  // namespace

std::string Command::option(const std::string& key, const std::string& fallback) const {
  for (const auto& [name, value] : options)
    if (name == key) return value;
  return fallback;
}

std::string Command::to_string() const {
  auto quote = [](const std::string& text) {
    return text.find(' ') == std::string::npos && !text.empty() ? text : '"' + text + '"';
  };
  std::string line = verb;
  for (const std::string& argument : arguments) line += ' ' + quote(argument);
  for (const auto& [key, value] : options) line += ' ' + key + '=' + quote(value);
  return line;
}

Command make_command(const std::string& verb, std::vector<std::string> arguments,
                     std::vector<std::pair<std::string, std::string>> options) {
  Command command;
  command.verb = verb;
  command.arguments = std::move(arguments);
  command.options = std::move(options);
  return command;
}

const std::vector<std::pair<std::string, std::string>>& command_synopses() {
  static const std::vector<std::pair<std::string, std::string>> list = [] {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Verb& verb : verbs()) out.emplace_back(verb.name, verb.synopsis);
    return out;
  }();
  return list;
}

bool parse_command(const std::string& line, int line_number, Command& command) {
  const std::vector<std::string> tokens = tokenize(line, line_number);
  if (tokens.empty()) return false;
  const Verb* verb = find_verb(tokens[0]);
  if (!verb) fail(line_number, "unknown command '" + tokens[0] + "' (see docs/gui.md)");
  Command parsed;
  parsed.verb = tokens[0];
  parsed.line = line_number;
  for (std::size_t i = 1; i < tokens.size(); ++i) {
    const std::size_t equals = tokens[i].find('=');
    if (equals == std::string::npos || equals == 0) {
      parsed.arguments.push_back(tokens[i]);
      continue;
    }
    const std::string key = tokens[i].substr(0, equals);
    if (std::find(verb->options.begin(), verb->options.end(), key) == verb->options.end())
      fail(line_number, parsed.verb + " takes no option '" + key + "'");
    parsed.options.emplace_back(key, tokens[i].substr(equals + 1));
  }
  const int count = static_cast<int>(parsed.arguments.size());
  if (count < verb->min_arguments || count > verb->max_arguments)
    fail(line_number, "usage: " + parsed.verb + " " + verb->synopsis);
  command = std::move(parsed);
  return true;
}

std::vector<Command> parse_script(const std::string& text) {
  std::vector<Command> commands;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    Command command;
    if (parse_command(line, number, command)) commands.push_back(std::move(command));
  }
  return commands;
}

std::vector<Command> read_script(const std::filesystem::path& path) {
  io::checked_input_size(path, io::kReadBudget.max_document_bytes);  // a regular file (not a FIFO)
  std::ifstream file(path);
  if (!file) throw InputError("cannot read the script " + path.string());
  std::ostringstream text;
  text << file.rdbuf();
  try {
    return parse_script(text.str());
  } catch (const UsageError& error) {
    throw UsageError(path.string() + ": " + error.what());
  }
}

}  // namespace partreg::ui
