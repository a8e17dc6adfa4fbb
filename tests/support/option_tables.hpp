#pragma once
// What the tests of the option tables share: the names a docs page's table of settings lists (the rows of the
// table headed "| name | value | default | meaning |", each starting with the option's name in backquotes),
// and the message of the UsageError a call throws.
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include "partreg/core/errors.hpp"

namespace partreg::testing {

/// Option names in the settings table of `docs/<page>` (empty when the page or the table is missing).
inline std::set<std::string> documented_options(const std::string& page) {
  std::ifstream file(std::string(PARTREG_SOURCE_DIR) + "/docs/" + page);
  std::set<std::string> documented;
  bool in_table = false;
  for (std::string line; std::getline(file, line);) {
    if (line.rfind("| name | value | default | meaning |", 0) == 0) in_table = true;
    if (in_table && line.empty()) break;
    if (in_table && line.rfind("| `", 0) == 0) documented.insert(line.substr(3, line.find('`', 3) - 3));
  }
  return documented;
}

/// The message of the UsageError `call` throws; empty when it throws none.
inline std::string usage_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

}  // namespace partreg::testing
