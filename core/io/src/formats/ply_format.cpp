#include "ply_format.hpp"

#include <fstream>
#include <map>
#include <sstream>

#include "header_lines.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

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

bool is_signed(const std::string& type) { return type == "char" || type == "short" || type == "int"; }

// Reads one list length of `type` (an integer type) from binary data in the file's byte order.
long long read_binary_count(std::istream& in, const std::string& type, bool big_endian) {
  unsigned char bytes[8] = {};
  const std::size_t size = ply_type_size(type);
  if (!in.read(reinterpret_cast<char*>(bytes), static_cast<std::streamsize>(size))) return -1;
  unsigned long long value = 0;
  for (std::size_t i = 0; i < size; ++i)
    value |= static_cast<unsigned long long>(bytes[big_endian ? size - 1 - i : i]) << (8 * i);
  if (is_signed(type) && size < 8 && (value >> (8 * size - 1)) & 1u)
    return static_cast<long long>(value) - (1ll << (8 * size));
  return static_cast<long long>(value);
}

// Reads one list length written as text; -1 when the data ends or the token is not a whole number.
long long read_ascii_count(std::istream& in) {
  double value = -1;
  if (!(in >> value) || value != static_cast<double>(static_cast<long long>(value))) return -1;
  return static_cast<long long>(value);
}

// Skips `count` values of `type` (binary) or `count` tokens (ASCII).
bool skip_values(std::istream& in, std::uint64_t count, const std::string& type, bool ascii) {
  if (!ascii)
    return static_cast<bool>(
        in.seekg(static_cast<std::streamoff>(count * ply_type_size(type)), std::ios::cur));
  std::string token;
  for (std::uint64_t i = 0; i < count; ++i)
    if (!(in >> token)) return false;
  return true;
}

bool has_list(const PlyElement& element) {
  for (const PlyProperty& property : element.properties)
    if (property.is_list) return true;
  return false;
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
  std::uint64_t budget = kReadBudget.max_header_bytes;
  if (!read_header_line(in, line, budget, file) || line.rfind("ply", 0) != 0)
    throw InputError(file + " is not a PLY file (no 'ply' magic)");
  PlyHeader header;
  bool has_format = false;
  while (read_header_line(in, line, budget, file)) {
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
      const bool faces = element.name == "face";
      check_count(file,
                  faces                      ? "faces"
                  : element.name == "vertex" ? "vertices"
                                             : element.name + " elements",
                  element.count, faces ? kReadBudget.max_faces : kReadBudget.max_points);
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
        property.count_type = normalised_type(count_type, file);
        property.type = normalised_type(item_type, file);
      } else {
        words >> property.name;
        property.type = normalised_type(type, file);
      }
      if (property.name.empty()) throw InputError(file + ": malformed PLY property line '" + line + "'");
      header.elements.back().properties.push_back(property);
    } else if (keyword == "comment") {
      header.comments.push_back(line.size() > 8 ? line.substr(8) : "");
    } else if (keyword != "obj_info" && !keyword.empty()) {
      // assimp aborts on some lines it does not know: the PLY grammar has no others.
      throw InputError(file + ": unknown PLY header line '" + line.substr(0, 40) +
                       "' (is end_header missing?)");
    }
  }
  throw InputError(file + ": PLY header has no end_header (truncated file?)");
}

void check_ply_body_fits(const PlyHeader& header, std::uint64_t available, const std::string& file) {
  const bool ascii = header.format == PlyHeader::Format::ascii;
  std::uint64_t used = 0;
  for (const PlyElement& element : header.elements) {
    std::uint64_t bytes_each = 0;  // an empty list still has its length
    for (const PlyProperty& property : element.properties)
      bytes_each += ascii ? 2 : ply_type_size(property.is_list ? property.count_type : property.type);
    check_fits(file, element.name == "vertex" ? "vertices" : element.name + " elements", element.count,
               bytes_each, available - used);
    used += element.count * bytes_each;  // fits: the check above bounds it by available
  }
}

PlyHeader read_checked_ply_header(std::istream& in, std::uint64_t file_size, const std::string& file) {
  const PlyHeader header = read_ply_header(in, file);
  const auto start = static_cast<std::uint64_t>(in.tellg());
  if (start > file_size) throw InputError(file + " is truncated (in its PLY header)");
  // ASCII files may end without a newline after their last value.
  const std::uint64_t slack = header.format == PlyHeader::Format::ascii ? 1 : 0;
  check_ply_body_fits(header, file_size - start + slack, file);
  return header;
}

PlyHeader read_checked_ply_header(const std::filesystem::path& path) {
  const std::uint64_t size = checked_input_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + path.string());
  return read_checked_ply_header(in, size, path.string());
}

void check_ply_face_lists(std::istream& in, const PlyHeader& header, const std::string& file) {
  const bool ascii = header.format == PlyHeader::Format::ascii;
  const bool big_endian = header.format == PlyHeader::Format::binary_big_endian;
  const std::string truncated = file + " is truncated (its PLY data ends before its faces do)";
  for (const PlyElement& element : header.elements) {
    const bool faces = element.name == "face";
    if (!ascii && !has_list(element)) {  // fixed-size rows: one jump
      std::uint64_t row = 0;
      for (const PlyProperty& property : element.properties) row += ply_type_size(property.type);
      if (!skip_values(in, element.count * row, "uchar", false)) throw InputError(truncated);
    } else {
      for (std::size_t item = 0; item < element.count; ++item)
        for (const PlyProperty& property : element.properties) {
          if (!property.is_list) {
            if (!skip_values(in, 1, property.type, ascii)) throw InputError(truncated);
            continue;
          }
          const long long count =
              ascii ? read_ascii_count(in) : read_binary_count(in, property.count_type, big_endian);
          if (!in) throw InputError(truncated);
          if (count < 0)
            throw InputError(file + ": PLY " + element.name + " " + std::to_string(item) + " has a list of " +
                             std::to_string(count) + " values");
          if (faces && count < 3)
            throw InputError(file + ": PLY face " + std::to_string(item) + " lists " + std::to_string(count) +
                             " vertices (a face needs at least 3)");
          if (!skip_values(in, static_cast<std::uint64_t>(count), property.type, ascii))
            throw InputError(truncated);
        }
    }
    if (faces) return;
  }
}

void check_ply_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::uint64_t size = checked_input_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + file);
  const PlyHeader header = read_checked_ply_header(in, size, file);
  check_ply_mesh_header(header, file);
  check_ply_face_lists(in, header, file);
}

void check_ply_mesh_header(const PlyHeader& header, const std::string& file) {
  for (const PlyElement& element : header.elements) {
    if (element.name != "vertex") continue;
    for (const char* axis : {"x", "y", "z"}) {
      bool found = false;
      for (const PlyProperty& property : element.properties)
        found |= property.name == axis && !property.is_list;
      if (!found) throw InputError(file + ": PLY vertices have no '" + axis + "' property");
    }
    return;
  }
  throw InputError(file + ": PLY file has no vertex element");
}

std::string part_name_comments(const std::vector<std::string>& part_names) {
  std::string lines;
  for (std::size_t p = 0; p < part_names.size(); ++p)
    lines += "comment part_name " + std::to_string(p) + ' ' + part_names[p] + '\n';
  return lines;
}

std::vector<std::string> part_names_from_comments(const std::vector<std::string>& comments) {
  constexpr std::size_t kMaxParts = 1000;  // a part index is small; a huge one is not a name of ours
  std::vector<std::string> names;
  for (const std::string& comment : comments) {
    std::istringstream words(comment);
    std::string keyword;
    std::size_t index = 0;
    if (!(words >> keyword >> index) || keyword != "part_name" || index >= kMaxParts) continue;
    std::string name;
    std::getline(words >> std::ws, name);
    if (names.size() <= index) names.resize(index + 1);
    names[index] = name;
  }
  return names;
}

}  // namespace partreg::io::detail
