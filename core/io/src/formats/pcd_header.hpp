#pragma once
// partreg's own check of a PCD header before its data is read (internal to partreg_io). The header is
// trusted by nothing until it passes here; this parser has no PCL dependency.

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace partreg::io::detail {

struct PcdField {
  std::string name;
  char type = 'F';  ///< I (signed), U (unsigned) or F (floating point)
  int size = 4;     ///< bytes per value: 1, 2, 4 or 8
  int count = 1;    ///< values per point
};

struct PcdHeader {
  enum class Data { ascii, binary, binary_compressed } data = Data::ascii;
  std::vector<PcdField> fields;
  std::uint64_t points = 0;
  std::uint32_t compressed_bytes = 0;  ///< binary_compressed: LZF bytes after the 8-byte size prefix
  std::uint64_t bytes_per_point() const;
  bool has_field(const std::string& name) const;
};

/// Parses the header from `in` (a file of `file_size` bytes) and checks it: fields, sizes, types and counts
/// that agree, x, y and z present, WIDTH x HEIGHT = POINTS within the reading budget, and data that can fit
/// into the rest of the file (for binary_compressed: the sizes its 8-byte prefix states). InputError naming
/// `file` otherwise.
PcdHeader read_checked_pcd_header(std::istream& in, std::uint64_t file_size, const std::string& file);

}  // namespace partreg::io::detail
