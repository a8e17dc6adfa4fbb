#include "pcd_reader.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <cstring>
#include <fstream>
#include <mutex>

#include "partreg/core/errors.hpp"
#include "pcd_header.hpp"

namespace partreg::io::detail {
namespace {

// PCL prints its own complaints to stderr; partreg's one-line message is the one that counts.
void silence_pcl() {
  static std::once_flag once;
  std::call_once(once, [] { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); });
}

const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (const auto& field : blob.fields)
    if (field.name == name) return &field;
  return nullptr;
}

std::size_t datatype_size(std::uint8_t datatype) {
  using F = pcl::PCLPointField;
  switch (datatype) {
    case F::INT8: case F::UINT8: return 1;
    case F::INT16: case F::UINT16: return 2;
    case F::INT32: case F::UINT32: case F::FLOAT32: return 4;
    case F::FLOAT64: return 8;
    default: return 0;  // INT64/UINT64 in newer PCL: not read
  }
}

// Reads value 0 of `field` at `point` as a double; the caller has checked that the field lies in the point.
double read_value(const pcl::PCLPointCloud2& blob, const pcl::PCLPointField& field, std::size_t point) {
  const std::uint8_t* at = blob.data.data() + point * blob.point_step + field.offset;
  auto as = [at](auto value) {
    std::memcpy(&value, at, sizeof value);
    return static_cast<double>(value);
  };
  using F = pcl::PCLPointField;
  switch (field.datatype) {
    case F::INT8: return as(std::int8_t{});
    case F::UINT8: return as(std::uint8_t{});
    case F::INT16: return as(std::int16_t{});
    case F::UINT16: return as(std::uint16_t{});
    case F::INT32: return as(std::int32_t{});
    case F::UINT32: return as(std::uint32_t{});
    case F::FLOAT32: return as(float{});
    default: return as(double{});
  }
}

// PCL's blob must agree with itself before any field is read from it.
void check_blob(const pcl::PCLPointCloud2& blob, const std::string& file) {
  const std::uint64_t points = static_cast<std::uint64_t>(blob.width) * blob.height;
  if (blob.point_step == 0 || blob.data.size() / blob.point_step < points)
    throw InputError("PCD file " + file + " holds less data than its header declares");
  for (const auto& field : blob.fields) {
    const std::size_t size = datatype_size(field.datatype);
    if (size == 0 || field.offset + size * std::max<std::uint32_t>(field.count, 1) > blob.point_step)
      throw InputError("PCD file " + file + ": field '" + field.name + "' does not fit in its point");
  }
}

Eigen::VectorXd column(const pcl::PCLPointCloud2& blob, const pcl::PCLPointField& field) {
  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  Eigen::VectorXd values(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) values[static_cast<Eigen::Index>(i)] = read_value(blob, field, i);
  return values;
}

bool is_integer(const pcl::PCLPointField& field) {
  using F = pcl::PCLPointField;
  return field.datatype != F::FLOAT32 && field.datatype != F::FLOAT64 && field.datatype != F::UINT32;
}

// A packed colour (PCL's rgb/rgba: bytes b, g, r, a of a 32-bit value) as three integer attributes.
void unpack_colour(const pcl::PCLPointCloud2& blob, const pcl::PCLPointField& field, PointAttributes& out) {
  if (datatype_size(field.datatype) != 4) return;
  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  Eigen::VectorXi red(static_cast<Eigen::Index>(n)), green(red.size()), blue(red.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t packed = 0;
    std::memcpy(&packed, blob.data.data() + i * blob.point_step + field.offset, 4);
    const auto row = static_cast<Eigen::Index>(i);
    red[row] = static_cast<int>((packed >> 16) & 0xff);
    green[row] = static_cast<int>((packed >> 8) & 0xff);
    blue[row] = static_cast<int>(packed & 0xff);
  }
  out.integers["red"] = red;
  out.integers["green"] = green;
  out.integers["blue"] = blue;
}

}  // namespace

CloudFile read_pcd(const std::filesystem::path& path, std::uint64_t file_size) {
  silence_pcl();
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  const PcdHeader header = read_checked_pcd_header(in, file_size, file);
  pcl::PCLPointCloud2 blob;
  if (pcl::PCDReader().read(file, blob) < 0) throw InputError("cannot read PCD file " + file);
  check_blob(blob, file);
  // PCL parses the header again, its own way: it must agree with partreg's reading of it.
  const std::uint64_t points = static_cast<std::uint64_t>(blob.width) * blob.height;
  if (points != header.points)
    throw InputError("PCD file " + file + ": PCL read " + std::to_string(points) + " points where its header declares " +
                     std::to_string(header.points));
  if (points == 0) throw InputError(file + " holds no points");
  const pcl::PCLPointField* axes[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
  if (!axes[0] || !axes[1] || !axes[2]) throw InputError("PCD file " + file + " has no x, y, z fields");
  CloudFile result;
  result.cloud.points.resize(static_cast<Eigen::Index>(blob.width) * blob.height, 3);
  for (int d = 0; d < 3; ++d) result.cloud.points.col(d) = column(blob, *axes[d]);
  const pcl::PCLPointField* normals[3] = {find_field(blob, "normal_x"), find_field(blob, "normal_y"),
                                          find_field(blob, "normal_z")};
  if (normals[0] && normals[1] && normals[2]) {
    result.cloud.normals.resize(result.cloud.points.rows(), 3);
    for (int d = 0; d < 3; ++d) result.cloud.normals.col(d) = column(blob, *normals[d]);
  }
  for (const auto& field : blob.fields) {
    const std::string& name = field.name;
    const bool geometry = name == "x" || name == "y" || name == "z" || (normals[0] && normals[1] && normals[2] &&
                                                                         name.rfind("normal_", 0) == 0);
    if (geometry || field.count != 1 || name == "_") continue;
    if (name == "rgb" || name == "rgba")
      unpack_colour(blob, field, result.attributes);
    else if (is_integer(field))
      result.attributes.integers[name] = column(blob, field).cast<int>();
    else
      result.attributes.reals[name] = column(blob, field);
  }
  return result;
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
