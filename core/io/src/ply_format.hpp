#pragma once
// PLY header parsing shared by the cloud reader and the mesh-or-cloud test (internal to partreg_io).

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace partreg::io::detail {

struct PlyProperty {
  std::string name;
  std::string type;  ///< scalar type, normalised to char/uchar/short/ushort/int/uint/float/double
  bool is_list = false;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  enum class Format { ascii, binary_little_endian, binary_big_endian } format = Format::ascii;
  std::vector<PlyElement> elements;
  std::size_t count_of(const std::string& element) const;
};

/// Parses the header and leaves `in` at the first byte of the data. Throws InputError naming `file`.
PlyHeader read_ply_header(std::istream& in, const std::string& file);

/// Size in bytes of a PLY scalar type.
std::size_t ply_type_size(const std::string& type);

}  // namespace partreg::io::detail
