#pragma once
/// \file
/// Script files: one command per line, `#` starts a comment, blank lines are skipped. Arguments are
/// separated by spaces; "double quotes" keep spaces inside one argument; `key=value` is an option.

#include <filesystem>
#include <string>
#include <vector>

#include "partreg/ui/commands.hpp"

namespace partreg::ui {

/// Parses one line into a command and checks its verb and argument count. Returns false for a blank or
/// comment-only line. Throws UsageError ("line N: ...") for an unknown verb, a wrong argument count, an
/// unterminated quote or an option the verb does not take.
bool parse_command(const std::string& line, int line_number, Command& command);

/// Parses a whole script text; UsageError names the first bad line.
std::vector<Command> parse_script(const std::string& text);

/// Reads and parses a script file; InputError when it cannot be read.
std::vector<Command> read_script(const std::filesystem::path& path);

}  // namespace partreg::ui
