#include "pcd_reader.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "partreg/core/errors.hpp"

namespace partreg::io::detail {
namespace {

bool has_field(const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (const auto& field : blob.fields)
    if (field.name == name) return true;
  return false;
}

}  // namespace

CloudFile read_pcd(const std::filesystem::path& path) {
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  // PCL prints its own complaints to stderr; our message below is the one that counts.
  if (reader.read(path.string(), blob) < 0) throw InputError("cannot read PCD file " + path.string());
  if (!has_field(blob, "x") || !has_field(blob, "y") || !has_field(blob, "z"))
    throw InputError("PCD file " + path.string() + " has no x, y, z fields");
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::fromPCLPointCloud2(blob, xyz);
  CloudFile file;
  file.cloud.points.resize(static_cast<Eigen::Index>(xyz.size()), 3);
  for (std::size_t i = 0; i < xyz.size(); ++i)
    file.cloud.points.row(static_cast<Eigen::Index>(i)) << xyz[i].x, xyz[i].y, xyz[i].z;
  if (has_field(blob, "normal_x") && has_field(blob, "normal_y") && has_field(blob, "normal_z")) {
    pcl::PointCloud<pcl::Normal> normals;
    pcl::fromPCLPointCloud2(blob, normals);
    file.cloud.normals.resize(static_cast<Eigen::Index>(normals.size()), 3);
    for (std::size_t i = 0; i < normals.size(); ++i)
      file.cloud.normals.row(static_cast<Eigen::Index>(i)) << normals[i].normal_x, normals[i].normal_y,
          normals[i].normal_z;
  }
  return file;
}

}  // namespace partreg::io::detail
