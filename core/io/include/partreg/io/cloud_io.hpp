#pragma once
/// \file
/// Point cloud files: PCD (ascii, binary, binary_compressed; through PCL), PLY (ascii and binary, any extra
/// per-vertex scalar properties) and XYZ text ("x y z [nx ny nz]" per line, '#' comments).

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>

#include "partreg/core/types.hpp"

namespace partreg::io {

/// Extra per-point values beyond position and normal (for example an integer `part`).
struct PointAttributes {
  std::map<std::string, Eigen::VectorXi> integers;
  std::map<std::string, Eigen::VectorXd> reals;
};

/// A cloud as read from a file. Points with a NaN or infinite coordinate are dropped (sensor clouds hold
/// them) and counted; attributes are filtered the same way.
struct CloudFile {
  core::Cloud cloud;
  PointAttributes attributes;
  std::size_t dropped_non_finite = 0;
};

/// Reads .pcd, .ply (vertices only, faces ignored), .xyz or .txt. Throws InputError naming the file for a
/// missing or unreadable file, an unknown extension, a malformed header, no points, or only NaN points.
CloudFile read_cloud_file(const std::filesystem::path& path);

/// Writes a PLY cloud (binary little-endian by default) with normals when present and every attribute as an
/// `int` or `float` vertex property. Atomic. Throws UsageError for attribute sizes that do not match.
void write_cloud_ply(const std::filesystem::path& path, const core::Cloud& cloud,
                     const PointAttributes& attributes = {}, bool binary = true);

}  // namespace partreg::io
