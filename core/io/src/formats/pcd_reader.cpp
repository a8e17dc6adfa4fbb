#include "pcd_reader.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "partreg/core/errors.hpp"
#include "pcd_header.hpp"

namespace partreg::io::detail {
namespace {

// PCL prints its own complaints to stderr; partreg's one-line message is the one that counts.
void silence_pcl() {
  static std::once_flag once;
  std::call_once(once, [] { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); });
}

// The points of a PCD file in one layout whatever its encoding: `points` rows of `step` bytes, each field's
// values at its offset in the file's own types (as DATA binary stores them). PCL's reader is not used for
// reading: it trusts its input and crashed on fuzzed files that pass the header check.
struct PointTable {
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint64_t> offsets;  ///< of each header field
  std::uint64_t step = 0;
  std::uint64_t points = 0;
};

PointTable empty_table(const PcdHeader& header) {
  PointTable table;
  for (const PcdField& field : header.fields) {
    table.offsets.push_back(table.step);
    table.step += static_cast<std::uint64_t>(field.size) * field.count;
  }
  table.points = header.points;
  table.bytes.resize(table.points * table.step);
  return table;
}

// One ASCII value stored in the field's type; a value the type cannot hold is refused, not wrapped.
void store_text_value(const std::string& word, const PcdField& field, std::uint8_t* at,
                      const std::string& where) {
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  if (word.empty() || *end != '\0') throw InputError(where + ": '" + word + "' is not a number");
  auto put = [at](auto typed) { std::memcpy(at, &typed, sizeof typed); };
  if (field.type == 'F') return field.size == 4 ? put(static_cast<float>(value)) : put(value);
  const bool is_signed = field.type == 'I';
  const double low = is_signed ? -std::ldexp(1.0, 8 * field.size - 1) : 0.0;
  const double high = std::ldexp(1.0, 8 * field.size - (is_signed ? 1 : 0));
  if (!(value >= low && value < high) || value != std::floor(value))
    throw InputError(where + ": '" + word + "' does not fit field '" + field.name + "' (" + field.type +
                     std::to_string(field.size) + ")");
  if (is_signed) {
    const auto integer = static_cast<std::int64_t>(value);
    if (field.size == 1) return put(static_cast<std::int8_t>(integer));
    if (field.size == 2) return put(static_cast<std::int16_t>(integer));
    return put(static_cast<std::int32_t>(integer));
  }
  const auto integer = static_cast<std::uint64_t>(value);
  if (field.size == 1) return put(static_cast<std::uint8_t>(integer));
  if (field.size == 2) return put(static_cast<std::uint16_t>(integer));
  put(static_cast<std::uint32_t>(integer));
}

bool is_blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

// DATA ascii: one point a line, exactly as many values as the fields declare (a ragged row is refused, not
// padded with zeros); blank lines are skipped.
PointTable read_ascii(std::istream& in, const PcdHeader& header, const std::string& file) {
  PointTable table = empty_table(header);
  std::string line;
  std::uint64_t point = 0;
  for (std::uint64_t line_number = 1; std::getline(in, line); ++line_number) {
    if (is_blank(line)) continue;
    const std::string where = file + ": PCD data line " + std::to_string(line_number);
    if (point == table.points) throw InputError(where + " holds more points than the header declares");
    std::istringstream words(line);
    std::string word;
    std::uint8_t* row = table.bytes.data() + point * table.step;
    for (std::size_t f = 0; f < header.fields.size(); ++f) {
      const PcdField& field = header.fields[f];
      for (int v = 0; v < field.count; ++v) {
        if (!(words >> word)) throw InputError(where + " has fewer values than the header's fields declare");
        store_text_value(word, field, row + table.offsets[f] + v * field.size, where);
      }
    }
    if (words >> word) throw InputError(where + " has more values than the header's fields declare");
    ++point;
  }
  if (point < table.points)
    throw InputError(file + " is truncated: it holds " + std::to_string(point) +
                     " PCD points, its header declares " + std::to_string(table.points));
  return table;
}

std::vector<std::uint8_t> read_exactly(std::istream& in, std::uint64_t size, const std::string& file) {
  std::vector<std::uint8_t> bytes(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    throw InputError(file + " is truncated (in its PCD data)");
  return bytes;
}

// LZF (as PCL writes it): a control byte below 32 starts a run of that many plus one literal bytes; any other
// copies (its top three bits, or 7 plus the next byte) plus two bytes from an earlier position. Every read
// and write is checked: a stream that would leave either buffer is refused.
std::vector<std::uint8_t> lzf_decompress(const std::vector<std::uint8_t>& in, std::uint64_t size,
                                         const std::string& file) {
  const std::string bad = file + ": PCD compressed data is corrupt";
  std::vector<std::uint8_t> out;
  out.reserve(size);
  std::size_t i = 0;
  while (i < in.size()) {
    const unsigned control = in[i++];
    if (control < 32) {
      const std::size_t run = control + 1;
      if (run > in.size() - i || run > size - out.size()) throw InputError(bad);
      out.insert(out.end(), in.begin() + static_cast<std::ptrdiff_t>(i),
                 in.begin() + static_cast<std::ptrdiff_t>(i + run));
      i += run;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (i == in.size()) throw InputError(bad);
      length += in[i++];
    }
    length += 2;
    if (i == in.size()) throw InputError(bad);
    const std::size_t back = ((control & 0x1f) << 8) + in[i++] + 1;
    if (back > out.size() || length > size - out.size()) throw InputError(bad);
    for (std::size_t k = 0, from = out.size() - back; k < length; ++k) out.push_back(out[from + k]);
  }
  if (out.size() != size) throw InputError(bad + " (it unpacks to fewer bytes than its header states)");
  return out;
}

PointTable read_binary(std::istream& in, const PcdHeader& header, const std::string& file) {
  PointTable table = empty_table(header);
  if (header.data == PcdHeader::Data::binary) {
    table.bytes = read_exactly(in, table.bytes.size(), file);
    return table;
  }
  // binary_compressed stores each field's values for all points together: turn it into rows.
  const std::vector<std::uint8_t> planar =
      lzf_decompress(read_exactly(in, header.compressed_bytes, file), table.bytes.size(), file);
  std::uint64_t from = 0;
  for (std::size_t f = 0; f < header.fields.size(); ++f) {
    const std::uint64_t width = static_cast<std::uint64_t>(header.fields[f].size) * header.fields[f].count;
    for (std::uint64_t point = 0; point < table.points; ++point, from += width)
      std::memcpy(table.bytes.data() + point * table.step + table.offsets[f], planar.data() + from, width);
  }
  return table;
}

// Value 0 of field `f` of every point as doubles.
Eigen::VectorXd column(const PointTable& table, const PcdField& field, std::size_t f) {
  Eigen::VectorXd values(static_cast<Eigen::Index>(table.points));
  for (std::uint64_t i = 0; i < table.points; ++i) {
    const std::uint8_t* at = table.bytes.data() + i * table.step + table.offsets[f];
    auto as = [at](auto value) {
      std::memcpy(&value, at, sizeof value);
      return static_cast<double>(value);
    };
    double& value = values[static_cast<Eigen::Index>(i)];
    if (field.type == 'F')
      value = field.size == 4 ? as(float{}) : as(double{});
    else if (field.type == 'I')
      value = field.size == 1 ? as(std::int8_t{}) : field.size == 2 ? as(std::int16_t{}) : as(std::int32_t{});
    else
      value = field.size == 1   ? as(std::uint8_t{})
              : field.size == 2 ? as(std::uint16_t{})
                                : as(std::uint32_t{});
  }
  return values;
}

// A packed colour (PCL's rgb/rgba: bytes b, g, r, a of a 32-bit value) as three integer attributes.
void unpack_colour(const PointTable& table, std::size_t f, PointAttributes& out) {
  const auto n = static_cast<Eigen::Index>(table.points);
  Eigen::VectorXi red(n), green(n), blue(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    std::uint32_t packed = 0;
    std::memcpy(&packed, table.bytes.data() + static_cast<std::uint64_t>(i) * table.step + table.offsets[f],
                4);
    red[i] = static_cast<int>((packed >> 16) & 0xff);
    green[i] = static_cast<int>((packed >> 8) & 0xff);
    blue[i] = static_cast<int>(packed & 0xff);
  }
  out.integers["red"] = red;
  out.integers["green"] = green;
  out.integers["blue"] = blue;
}

std::ptrdiff_t field_index(const PcdHeader& header, const std::string& name) {
  for (std::size_t f = 0; f < header.fields.size(); ++f)
    if (header.fields[f].name == name) return static_cast<std::ptrdiff_t>(f);
  return -1;
}

// x, y, z (and normal_x/y/z when all three are present) as geometry; every other one-value field as an
// attribute: integer types as integers, floating point and 32-bit unsigned as reals.
CloudFile cloud_from_table(const PointTable& table, const PcdHeader& header) {
  CloudFile result;
  result.cloud.points.resize(static_cast<Eigen::Index>(table.points), 3);
  const char* axes[3] = {"x", "y", "z"};
  const char* normal_axes[3] = {"normal_x", "normal_y", "normal_z"};
  bool has_normals = true;
  for (const char* name : normal_axes) has_normals = has_normals && field_index(header, name) >= 0;
  if (has_normals) result.cloud.normals.resize(result.cloud.points.rows(), 3);
  for (int d = 0; d < 3; ++d) {
    const auto f = static_cast<std::size_t>(field_index(header, axes[d]));
    result.cloud.points.col(d) = column(table, header.fields[f], f);
    if (!has_normals) continue;
    const auto n = static_cast<std::size_t>(field_index(header, normal_axes[d]));
    result.cloud.normals.col(d) = column(table, header.fields[n], n);
  }
  for (std::size_t f = 0; f < header.fields.size(); ++f) {
    const PcdField& field = header.fields[f];
    const std::string& name = field.name;
    const bool geometry =
        name == "x" || name == "y" || name == "z" || (has_normals && name.rfind("normal_", 0) == 0);
    if (geometry || field.count != 1 || name == "_") continue;
    if (name == "rgb" || name == "rgba") {
      if (field.size == 4) unpack_colour(table, f, result.attributes);
    } else if (field.type == 'F' || (field.type == 'U' && field.size == 4)) {
      result.attributes.reals[name] = column(table, field, f);
    } else {
      result.attributes.integers[name] = column(table, field, f).cast<int>();
    }
  }
  return result;
}

}  // namespace

CloudFile read_pcd(const std::filesystem::path& path, std::uint64_t file_size) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + file + " for reading");
  const PcdHeader header = read_checked_pcd_header(in, file_size, file);
  if (header.points == 0) throw InputError(file + " holds no points");
  for (const char* axis : {"x", "y", "z"})
    if (header.fields[static_cast<std::size_t>(field_index(header, axis))].count != 1)
      throw InputError("PCD file " + file + ": field '" + axis + "' must hold one value per point");
  const PointTable table =
      header.data == PcdHeader::Data::ascii ? read_ascii(in, header, file) : read_binary(in, header, file);
  return cloud_from_table(table, header);
}

void write_pcd(std::ostream& out, const core::Cloud& cloud, const PointAttributes& attributes) {
  silence_pcl();
  const Eigen::Index n = cloud.points.rows();
  const bool has_normals = cloud.normals.rows() == n && n > 0;
  pcl::PCLPointCloud2 blob;
  auto add_field = [&](const std::string& name, std::uint8_t datatype) {
    pcl::PCLPointField field;
    field.name = name;
    field.offset = blob.point_step;
    field.datatype = datatype;
    field.count = 1;
    blob.fields.push_back(field);
    blob.point_step += 4;
  };
  for (const char* name : {"x", "y", "z"}) add_field(name, pcl::PCLPointField::FLOAT32);
  if (has_normals)
    for (const char* name : {"normal_x", "normal_y", "normal_z"}) add_field(name, pcl::PCLPointField::FLOAT32);
  for (const auto& entry : attributes.integers) add_field(entry.first, pcl::PCLPointField::INT32);
  for (const auto& entry : attributes.reals) add_field(entry.first, pcl::PCLPointField::FLOAT32);
  blob.width = static_cast<std::uint32_t>(n);
  blob.height = 1;
  blob.is_dense = false;
  blob.row_step = blob.point_step * blob.width;
  blob.data.resize(static_cast<std::size_t>(blob.row_step));
  std::uint8_t* at = blob.data.data();
  auto put = [&at](auto value) {
    std::memcpy(at, &value, sizeof value);
    at += sizeof value;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) put(static_cast<float>(cloud.points(i, d)));
    if (has_normals)
      for (int d = 0; d < 3; ++d) put(static_cast<float>(cloud.normals(i, d)));
    for (const auto& entry : attributes.integers) put(static_cast<std::int32_t>(entry.second[i]));
    for (const auto& entry : attributes.reals) put(static_cast<float>(entry.second[i]));
  }
  // PCL writes binary PCDs through mmap, which fails on a FIFO or a device: PCL makes the header, the
  // bytes go to any stream.
  out << pcl::PCDWriter().generateHeaderBinary(blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity())
      << "DATA binary\n";
  out.write(reinterpret_cast<const char*>(blob.data.data()), static_cast<std::streamsize>(blob.data.size()));
}

}  // namespace partreg::io::detail
