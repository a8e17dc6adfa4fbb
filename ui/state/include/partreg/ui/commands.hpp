#pragma once
/// \file
/// The commands that change the desktop app's state. Panels emit them, scripts are read into them, and
/// execute() (executor.hpp) is the only code that applies them. The text form of each is one script line;
/// the language is documented in docs/gui.md.

#include <string>
#include <vector>

namespace partreg::ui {

/// One command: a verb and its arguments, already checked by parse_command (script.hpp). Positional
/// arguments keep their order; `key=value` options are kept apart.
struct Command {
  std::string verb;                                          ///< e.g. "paint"
  std::vector<std::string> arguments;                        ///< positional, in order
  std::vector<std::pair<std::string, std::string>> options;  ///< key=value, in order
  int line = 0;                                              ///< script line (1-based), 0 when from a panel

  /// The value of option `key`, or `fallback` when absent.
  std::string option(const std::string& key, const std::string& fallback = "") const;
  /// The command as one script line (quoting arguments that hold spaces).
  std::string to_string() const;
};

/// Makes a command from a verb and positional arguments (what panels call).
Command make_command(const std::string& verb, std::vector<std::string> arguments = {},
                     std::vector<std::pair<std::string, std::string>> options = {});

/// Every verb with its argument synopsis, for `--help` and the docs.
const std::vector<std::pair<std::string, std::string>>& command_synopses();

}  // namespace partreg::ui
