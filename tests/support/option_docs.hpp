#pragma once
// The names a docs page's table of settings lists: the rows of the table headed
// "| name | value | default | meaning |", each starting with the option's name in backquotes.
#include <fstream>
#include <set>
#include <string>

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

}  // namespace partreg::testing
