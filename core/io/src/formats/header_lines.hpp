#pragma once
// Reading the text header of a PLY, PCD or OFF file line by line without trusting it (internal to partreg_io).

#include <istream>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io::detail {

/// Reads one header line (without its '\n' or '\r\n') from `in`, counting its bytes against `budget`.
/// Returns false at the end of the file. A header longer than the budget (a binary file, or a text file
/// without the line that ends the header) is an InputError naming `file`, not a long read.
inline bool read_header_line(std::istream& in, std::string& line, std::uint64_t& budget,
                             const std::string& file) {
  line.clear();
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
    if (budget-- == 0)
      throw InputError(file + ": its header is longer than " + std::to_string(kReadBudget.max_header_bytes) +
                       " bytes (not a valid header, or its end line is missing)");
    if (c == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return true;
    }
    line += static_cast<char>(c);
  }
  return !line.empty();
}

}  // namespace partreg::io::detail
