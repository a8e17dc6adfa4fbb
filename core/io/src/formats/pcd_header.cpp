#include "pcd_header.hpp"

#include <cstring>
#include <set>
#include <sstream>

#include "header_lines.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io::detail {
namespace {

constexpr std::uint64_t kMaxValuesPerPoint = 4096;  // PCL's widest point types hold a few hundred

std::vector<std::string> words_after_keyword(std::istringstream& words) {
  std::vector<std::string> values;
  for (std::string word; words >> word;) values.push_back(word);
  return values;
}

// A non-negative integer that fits the budget, or an InputError naming the header line.
std::uint64_t parse_count(const std::string& word, const std::string& key, const std::string& file) {
  if (word.empty() || word.size() > 18 || word.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(file + ": PCD " + key + " must be a non-negative integer, not '" + word + "'");
  return std::stoull(word);
}

// Fills sizes, types or counts of the fields from one header line.
void set_field_property(PcdHeader& header, const std::string& key, const std::vector<std::string>& values,
                        const std::string& file) {
  if (values.size() != header.fields.size())
    throw InputError(file + ": PCD " + key + " lists " + std::to_string(values.size()) + " values for " +
                     std::to_string(header.fields.size()) + " fields (FIELDS must come first)");
  for (std::size_t i = 0; i < values.size(); ++i) {
    PcdField& field = header.fields[i];
    if (key == "TYPE") {
      if (values[i] != "I" && values[i] != "U" && values[i] != "F")
        throw InputError(file + ": PCD TYPE of field '" + field.name + "' must be I, U or F");
      field.type = values[i][0];
    } else {
      const std::uint64_t value = parse_count(values[i], key, file);
      if (key == "SIZE" && value != 1 && value != 2 && value != 4 && value != 8)
        throw InputError(file + ": PCD SIZE of field '" + field.name + "' must be 1, 2, 4 or 8");
      if (key == "COUNT" && (value < 1 || value > kMaxValuesPerPoint))
        throw InputError(file + ": PCD COUNT of field '" + field.name + "' is out of range");
      (key == "SIZE" ? field.size : field.count) = static_cast<int>(value);
    }
  }
}

void check_fields(const PcdHeader& header, const std::string& file) {
  std::uint64_t values = 0;
  for (const PcdField& field : header.fields) {
    if (field.type == 'F' && field.size != 4 && field.size != 8)
      throw InputError(file + ": PCD field '" + field.name + "' is floating point of size " +
                       std::to_string(field.size) + " (only 4 or 8)");
    if (field.type != 'F' && field.size == 8)  // PCL 1.13 reads 64-bit integers inconsistently
      throw InputError(file + ": PCD field '" + field.name + "' is a 64-bit integer (not supported)");
    values += static_cast<std::uint64_t>(field.count);
  }
  if (values > kMaxValuesPerPoint) throw InputError(file + ": PCD points have too many values");
  for (const char* axis : {"x", "y", "z"})
    if (!header.has_field(axis)) throw InputError(file + ": PCD file has no '" + axis + "' field");
}

void check_body(PcdHeader& header, std::istream& in, std::uint64_t available, const std::string& file) {
  if (header.data == PcdHeader::Data::binary) {
    check_fits(file, "points", header.points, header.bytes_per_point(), available);
    return;
  }
  if (header.data == PcdHeader::Data::ascii) {
    std::uint64_t values = 0;
    for (const PcdField& field : header.fields) values += static_cast<std::uint64_t>(field.count);
    check_fits(file, "points", header.points, 2 * values, available + 1);  // last value without '\n'
    return;
  }
  std::uint32_t sizes[2] = {};  // compressed, uncompressed
  if (available < sizeof sizes || !in.read(reinterpret_cast<char*>(sizes), sizeof sizes))
    throw InputError(file + ": PCD binary_compressed data is missing its sizes");
  if (sizes[0] > available - sizeof sizes)
    throw InputError(file + " is truncated: its compressed data claims " + std::to_string(sizes[0]) +
                     " bytes but " + std::to_string(available - sizeof sizes) + " follow");
  if (sizes[1] != header.points * header.bytes_per_point())
    throw InputError(file + ": PCD compressed data would unpack to " + std::to_string(sizes[1]) +
                     " bytes, not the " + std::to_string(header.points * header.bytes_per_point()) +
                     " its header declares");
  if (header.points > 0 && sizes[0] == 0) throw InputError(file + ": PCD compressed data is empty");
  header.compressed_bytes = sizes[0];
}

// PCL splits header lines at spaces, tabs and carriage returns only; other control characters (a vertical
// tab, a NUL) would make its reading of the line differ from partreg's.
void check_header_characters(const std::string& line, const std::string& file) {
  for (unsigned char c : line)
    if (c < 0x20 && c != '\t' && c != '\r')
      throw InputError(file + ": PCD header holds a control character (not a PCD file?)");
}

}  // namespace

std::uint64_t PcdHeader::bytes_per_point() const {
  std::uint64_t bytes = 0;
  for (const PcdField& field : fields) bytes += static_cast<std::uint64_t>(field.size) * field.count;
  return bytes;
}

bool PcdHeader::has_field(const std::string& name) const {
  for (const PcdField& field : fields)
    if (field.name == name) return true;
  return false;
}

PcdHeader read_checked_pcd_header(std::istream& in, std::uint64_t file_size, const std::string& file) {
  PcdHeader header;
  std::uint64_t budget = kReadBudget.max_header_bytes;
  std::uint64_t width = 0, height = 0;
  bool has_width = false, has_height = false, has_points = false;
  std::string line;
  while (read_header_line(in, line, budget, file)) {
    check_header_characters(line, file);
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    // PCL takes any other line for the first line of data and then reads without fields: refuse it here.
    static const std::set<std::string> known = {"VERSION", "FIELDS", "COLUMNS", "SIZE",   "TYPE", "COUNT",
                                                "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (!known.count(key)) throw InputError(file + ": unknown PCD header line '" + key + "' (not a PCD file?)");
    const std::vector<std::string> values = words_after_keyword(words);
    if (key == "FIELDS" || key == "COLUMNS") {
      if (!header.fields.empty()) throw InputError(file + ": PCD header lists FIELDS twice");
      if (values.empty() || values.size() > kMaxValuesPerPoint)
        throw InputError(file + ": PCD FIELDS line is empty or too long");
      for (const std::string& name : values) header.fields.push_back({name});
      continue;
    }
    if (key == "SIZE" || key == "TYPE" || key == "COUNT") {
      set_field_property(header, key, values, file);
      continue;
    }
    const std::string first = values.empty() ? "" : values.front();
    if (key == "WIDTH") width = parse_count(first, key, file), has_width = true;
    if (key == "HEIGHT") height = parse_count(first, key, file), has_height = true;
    if (key == "POINTS") header.points = parse_count(first, key, file), has_points = true;
    if (key == "DATA") {
      if (first == "ascii") header.data = PcdHeader::Data::ascii;
      else if (first == "binary") header.data = PcdHeader::Data::binary;
      else if (first == "binary_compressed") header.data = PcdHeader::Data::binary_compressed;
      else throw InputError(file + ": unknown PCD DATA encoding '" + first + "'");
      if (header.fields.empty() || !has_width || !has_height)
        throw InputError(file + ": PCD header lacks FIELDS, WIDTH or HEIGHT before DATA");
      check_fields(header, file);
      check_count(file, "points", width, kReadBudget.max_points);
      check_count(file, "points", height, kReadBudget.max_points);
      if (!has_points) header.points = width * height;
      check_count(file, "points", header.points, kReadBudget.max_points);
      if (width * height != header.points)
        throw InputError(file + ": PCD WIDTH x HEIGHT is not POINTS");
      const auto start = static_cast<std::uint64_t>(in.tellg());
      if (!in || start > file_size) throw InputError(file + " is truncated (in its PCD header)");
      check_body(header, in, file_size - start, file);
      return header;
    }
  }
  throw InputError(file + " is not a PCD file (its header has no DATA line)");
}

}  // namespace partreg::io::detail
