#include "ply_format.hpp"

#include <map>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::io::detail {
namespace {

std::string normalised_type(const std::string& type, const std::string& file) {
  static const std::map<std::string, std::string> aliases = {
      {"char", "char"},   {"int8", "char"},     {"uchar", "uchar"},   {"uint8", "uchar"},
      {"short", "short"}, {"int16", "short"},   {"ushort", "ushort"}, {"uint16", "ushort"},
      {"int", "int"},     {"int32", "int"},     {"uint", "uint"},     {"uint32", "uint"},
      {"float", "float"}, {"float32", "float"}, {"double", "double"}, {"float64", "double"}};
  const auto found = aliases.find(type);
  if (found == aliases.end()) throw InputError(file + ": unknown PLY property type '" + type + "'");
  return found->second;
}

}  // namespace

std::size_t PlyHeader::count_of(const std::string& element) const {
  for (const PlyElement& candidate : elements)
    if (candidate.name == element) return candidate.count;
  return 0;
}

std::size_t ply_type_size(const std::string& type) {
  if (type == "char" || type == "uchar") return 1;
  if (type == "short" || type == "ushort") return 2;
  if (type == "double") return 8;
  return 4;
}

PlyHeader read_ply_header(std::istream& in, const std::string& file) {
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0)
    throw InputError(file + " is not a PLY file (no 'ply' magic)");
  PlyHeader header;
  bool has_format = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") {
      if (!has_format) throw InputError(file + ": PLY header has no format line");
      return header;
    }
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format == "ascii")
        header.format = PlyHeader::Format::ascii;
      else if (format == "binary_little_endian")
        header.format = PlyHeader::Format::binary_little_endian;
      else if (format == "binary_big_endian")
        header.format = PlyHeader::Format::binary_big_endian;
      else
        throw InputError(file + ": unknown PLY format '" + format + "'");
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      long long count = -1;
      words >> element.name >> count;
      if (!words || count < 0) throw InputError(file + ": malformed PLY element line '" + line + "'");
      element.count = static_cast<std::size_t>(count);
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) throw InputError(file + ": PLY property before any element");
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> property.name;
        property.is_list = true;
        property.type = normalised_type(item_type, file);
      } else {
        words >> property.name;
        property.type = normalised_type(type, file);
      }
      if (property.name.empty()) throw InputError(file + ": malformed PLY property line '" + line + "'");
      header.elements.back().properties.push_back(property);
    }
    // comment, obj_info and unknown lines are ignored
  }
  throw InputError(file + ": PLY header has no end_header (truncated file?)");
}

}  // namespace partreg::io::detail
