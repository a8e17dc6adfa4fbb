#include "partreg/io/cloud_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/output_format.hpp"
#include "partreg/io/read_limits.hpp"
#include "pcd_reader.hpp"
#include "ply_format.hpp"
#include "vtk_io.hpp"

namespace partreg::io {
namespace {

using detail::PlyHeader;

// Reads one scalar of `type` in the file's encoding, as a double.
double read_scalar(std::istream& in, const std::string& type, PlyHeader::Format format,
                   const std::string& file) {
  if (format == PlyHeader::Format::ascii) {
    // A word, then strtod: "nan" and "inf" read (such points are dropped later, as in every format), and a
    // word that is no number is named, not reported as the end of the file.
    std::string word;
    if (!(in >> word)) return 0.0;  // the stream's failure says: truncated
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (*end != '\0') throw InputError(file + ": PLY value '" + word + "' is not a number");
    return value;
  }
  unsigned char bytes[8] = {};
  const std::size_t size = detail::ply_type_size(type);
  in.read(reinterpret_cast<char*>(bytes), static_cast<std::streamsize>(size));
  if (format == PlyHeader::Format::binary_big_endian)
    std::reverse(bytes, bytes + size);  // files are LE or BE; we are LE
  auto as = [&](auto value) {
    std::memcpy(&value, bytes, sizeof value);
    return static_cast<double>(value);
  };
  if (type == "char") return as(std::int8_t{});
  if (type == "uchar") return as(std::uint8_t{});
  if (type == "short") return as(std::int16_t{});
  if (type == "ushort") return as(std::uint16_t{});
  if (type == "int") return as(std::int32_t{});
  if (type == "uint") return as(std::uint32_t{});
  if (type == "float") return as(float{});
  return as(double{});
}

bool is_integer_type(const std::string& type) { return type != "float" && type != "double"; }

// An integer property as ints: a value beyond int (a uint of 4e9, "1e300" or "nan" in an ASCII file) is
// refused, since casting it would be undefined.
Eigen::VectorXi checked_integers(const Eigen::VectorXd& values, const std::string& file, const std::string& name) {
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (!(std::abs(values[i]) <= 2147483647.0))
      throw InputError(file + ": integer property '" + name + "' holds a value beyond the int range");
  return values.cast<int>();
}

CloudFile read_ply_cloud(const std::filesystem::path& path, std::uint64_t file_size) {
  std::ifstream in(path, std::ios::binary);
  const std::string file = path.string();
  const PlyHeader header = detail::read_checked_ply_header(in, file_size, file);
  if (header.elements.empty() || header.elements.front().name != "vertex")
    throw InputError(file + ": the first PLY element must be 'vertex'");
  const detail::PlyElement& vertex = header.elements.front();
  const auto n = static_cast<Eigen::Index>(vertex.count);
  if (n == 0) throw InputError(file + " holds no points");
  std::map<std::string, Eigen::VectorXd> columns;
  for (const auto& property : vertex.properties) {
    if (property.is_list)
      throw InputError(file + ": list property '" + property.name + "' on vertices is not supported");
    columns[property.name].resize(n);
  }
  for (const char* axis : {"x", "y", "z"})
    if (!columns.count(axis)) throw InputError(file + ": PLY vertices have no '" + axis + "' property");
  for (Eigen::Index i = 0; i < n; ++i)
    for (const auto& property : vertex.properties)
      columns[property.name][i] = read_scalar(in, property.type, header.format, file);
  if (!in) throw InputError(file + " is truncated: it ends before its " + std::to_string(n) + " vertices");

  CloudFile result;
  result.cloud.points.resize(n, 3);
  result.cloud.points << columns["x"], columns["y"], columns["z"];
  const bool has_normals = columns.count("nx") && columns.count("ny") && columns.count("nz");
  if (has_normals) {
    result.cloud.normals.resize(n, 3);
    result.cloud.normals << columns["nx"], columns["ny"], columns["nz"];
  }
  for (const auto& property : vertex.properties) {
    static const std::set<std::string> geometry = {"x", "y", "z", "nx", "ny", "nz"};
    if (geometry.count(property.name) && (has_normals || property.name.size() == 1)) continue;
    if (is_integer_type(property.type))
      result.attributes.integers[property.name] = checked_integers(columns[property.name], file, property.name);
    else
      result.attributes.reals[property.name] = columns[property.name];
  }
  result.attributes.part_names = detail::part_names_from_comments(header.comments);
  return result;
}

// Columns 4-6 of an XYZ file are normals only when every row's are a unit vector; anything else (colours,
// intensities) is kept as attributes, never silently dropped.
void split_xyz_columns(const Eigen::MatrixXd& table, CloudFile& result) {
  result.cloud.points = table.leftCols(3);
  if (table.cols() == 3) return;
  const Eigen::MatrixXd extra = table.rightCols(3);
  const bool unit_rows = ((extra.rowwise().norm().array() - 1.0).abs() < 1e-3).all();
  if (unit_rows) {
    result.cloud.normals = extra;
    return;
  }
  const bool bytes = (extra.array() == extra.array().round()).all() && extra.minCoeff() >= 0.0 &&
                     extra.maxCoeff() <= 255.0;
  const char* names[3] = {"red", "green", "blue"};
  for (int c = 0; c < 3; ++c) {
    if (bytes)
      result.attributes.integers[names[c]] = extra.col(c).cast<int>();
    else
      result.attributes.reals[names[c]] = extra.col(c);
  }
}

CloudFile read_xyz(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<double> values;
  std::size_t columns = 0, line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    const auto comment = line.find('#');
    if (comment != std::string::npos) line.erase(comment);
    std::istringstream words(line);
    std::vector<double> row;
    for (std::string word; words >> word;) {
      char* end = nullptr;
      row.push_back(std::strtod(word.c_str(), &end));
      if (*end != '\0')
        throw InputError(path.string() + ":" + std::to_string(line_number) + ": not a number: '" + word +
                         "'");
    }
    if (row.empty()) continue;
    if (columns == 0) columns = row.size();
    if (row.size() != columns || (columns != 3 && columns != 6))
      throw InputError(path.string() + ":" + std::to_string(line_number) +
                       ": expected 3 or 6 numbers per line");
    values.insert(values.end(), row.begin(), row.end());
    check_count(path.string(), "points", values.size() / columns, kReadBudget.max_points);
  }
  CloudFile result;
  const auto n = static_cast<Eigen::Index>(columns ? values.size() / columns : 0);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> table(
      values.data(), n, static_cast<Eigen::Index>(columns));
  if (n > 0) split_xyz_columns(table, result);
  return result;
}

// Drops rows with a non-finite coordinate from the points and everything that runs parallel to them.
void drop_non_finite(CloudFile& file, const std::string& name) {
  const Eigen::Index n = file.cloud.points.rows();
  if (n == 0) throw InputError(name + " holds no points");
  std::vector<int> keep;
  for (Eigen::Index i = 0; i < n; ++i)
    if (file.cloud.points.row(i).allFinite()) keep.push_back(static_cast<int>(i));
  if (keep.empty())
    throw InputError("all " + std::to_string(n) + " points of " + name + " are NaN or infinite");
  file.dropped_non_finite = static_cast<std::size_t>(n) - keep.size();
  if (file.dropped_non_finite == 0) return;
  file.cloud.points = file.cloud.points(keep, Eigen::all).eval();
  if (file.cloud.normals.rows() == n) file.cloud.normals = file.cloud.normals(keep, Eigen::all).eval();
  for (auto& [key, values] : file.attributes.integers) values = values(keep).eval();
  for (auto& [key, values] : file.attributes.reals) values = values(keep).eval();
}

// The PLY bytes of a cloud (binary little-endian or ASCII).
void put_ply(std::ostream& out, const core::Cloud& cloud, const PointAttributes& attributes, bool binary) {
  const Eigen::Index n = cloud.points.rows();
  const bool normals = cloud.normals.rows() == n && n > 0;
  {
    out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii")
        << " 1.0\ncomment written by partreg\n"
        << detail::part_name_comments(attributes.part_names) << "element vertex " << n
        << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
    for (const auto& entry : attributes.integers) out << "property int " << entry.first << '\n';
    for (const auto& entry : attributes.reals) out << "property float " << entry.first << '\n';
    out << "end_header\n";
    out.precision(9);
    auto put_float = [&](double value, bool last) {
      const float f = static_cast<float>(value);
      if (binary)
        out.write(reinterpret_cast<const char*>(&f), 4);
      else
        out << f << (last ? '\n' : ' ');
    };
    auto put_int = [&](int value, bool last) {
      if (binary)
        out.write(reinterpret_cast<const char*>(&value), 4);
      else
        out << value << (last ? '\n' : ' ');
    };
    const std::size_t extra = attributes.integers.size() + attributes.reals.size();
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int d = 0; d < 3; ++d) put_float(cloud.points(i, d), !normals && extra == 0 && d == 2);
      if (normals)
        for (int d = 0; d < 3; ++d) put_float(cloud.normals(i, d), extra == 0 && d == 2);
      std::size_t written = 0;
      for (const auto& entry : attributes.integers) put_int(entry.second[i], ++written == extra);
      for (const auto& entry : attributes.reals) put_float(entry.second[i], ++written == extra);
    }
  }
}

void put_xyz(std::ostream& out, const core::Cloud& cloud) {
  const bool normals = cloud.normals.rows() == cloud.points.rows();
  out.precision(9);
  for (Eigen::Index i = 0; i < cloud.points.rows(); ++i) {
    out << cloud.points(i, 0) << ' ' << cloud.points(i, 1) << ' ' << cloud.points(i, 2);
    if (normals) out << ' ' << cloud.normals(i, 0) << ' ' << cloud.normals(i, 1) << ' ' << cloud.normals(i, 2);
    out << '\n';
  }
}

void check_attribute_sizes(const core::Cloud& cloud, const PointAttributes& attributes) {
  const Eigen::Index n = cloud.points.rows();
  auto check = [n](const std::string& name, Eigen::Index size) {
    if (size != n)
      throw UsageError("attribute '" + name + "' has " + std::to_string(size) + " values for " +
                       std::to_string(n) + " points");
  };
  for (const auto& [name, values] : attributes.integers) check(name, values.size());
  for (const auto& [name, values] : attributes.reals) check(name, values.size());
}

CloudFile cloud_from_vtp(const std::filesystem::path& path) {
  detail::PolyData data = detail::read_vtp(path);
  if (data.points.rows() == 0) throw InputError(path.string() + " holds no points");
  CloudFile file;
  file.cloud.points = std::move(data.points);
  file.cloud.normals = std::move(data.normals);
  file.attributes = std::move(data.attributes);
  return file;
}

}  // namespace

CloudFile read_cloud_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::uint64_t size = checked_input_size(path);
  const std::string extension = lower_extension(path);
  CloudFile file;
  if (extension == ".pcd")
    file = detail::read_pcd(path, size);
  else if (extension == ".ply")
    file = read_ply_cloud(path, size);
  else if (extension == ".xyz" || extension == ".txt")
    file = read_xyz(path);
  else if (extension == ".vtp")
    file = cloud_from_vtp(path);
  else
    throw InputError(name + ": unknown point cloud extension '" + extension +
                     "' (expected .pcd, .ply, .vtp, .xyz, .txt)");
  drop_non_finite(file, name);
  // 1e300 squared overflows: sampling looped forever and CPD returned NaN. 1e12 bounds every coordinate.
  if (file.cloud.points.size() > 0 && file.cloud.points.cwiseAbs().maxCoeff() > 1e12)
    throw InputError(name + " holds coordinates beyond 1e12, not a sensible size");
  return file;
}

void write_cloud(const std::filesystem::path& path, const core::Cloud& cloud, const PointAttributes& attributes,
                 PlyEncoding encoding) {
  const FileFormat format = output_format(path, OutputKind::cloud);
  check_attribute_sizes(cloud, attributes);
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (format == FileFormat::ply) put_ply(out, cloud, attributes, encoding == PlyEncoding::binary);
    if (format == FileFormat::pcd) detail::write_pcd(out, cloud, attributes);
    if (format == FileFormat::xyz) put_xyz(out, cloud);
    if (format == FileFormat::vtp) detail::write_vtp(out, {cloud.points, cloud.normals, {}, attributes});
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

void write_cloud_ply(const std::filesystem::path& path, const core::Cloud& cloud,
                     const PointAttributes& attributes, bool binary) {
  if (output_format(path, OutputKind::cloud) != FileFormat::ply)
    throw UsageError("cannot write PLY bytes to " + path.string() + ": its extension names another format");
  write_cloud(path, cloud, attributes, binary ? PlyEncoding::binary : PlyEncoding::ascii);
}

}  // namespace partreg::io
