#pragma once
/// \file
/// Point cloud files: PCD (ascii, binary, binary_compressed; through PCL, its header checked by partreg
/// first), PLY (ascii and binary, any extra per-vertex scalar properties), ParaView's PolyData (.vtp, through
/// VTK) and XYZ text ("x y z [a b c]" per line, '#' comments: a b c are normals when every row's are a unit
/// vector, otherwise red, green, blue attributes). Every header's counts are checked against the file's size
/// and the reading budget (read_limits.hpp) before anything is allocated.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::io {

/// Extra per-point values beyond position and normal (for example an integer `part`).
struct PointAttributes {
  std::map<std::string, Eigen::VectorXi> integers;
  std::map<std::string, Eigen::VectorXd> reals;
  /// The name of each value of the integer `part` (index = value), when known: .ply files keep them as
  /// "comment part_name INDEX NAME" header lines, .vtp files as the field-data string array `part_names`.
  std::vector<std::string> part_names;
};

/// A cloud as read from a file. Points with a NaN or infinite coordinate are dropped (sensor clouds hold
/// them) and counted; attributes are filtered the same way.
struct CloudFile {
  core::Cloud cloud;
  PointAttributes attributes;
  std::size_t dropped_non_finite = 0;
};

/// Reads .pcd, .ply (vertices only, faces ignored), .vtp (points and point arrays), .xyz or .txt. Throws
/// InputError naming the file for a missing or unreadable file, an unknown extension, a malformed header,
/// counts the file cannot hold or beyond the reading budget, no points, or only NaN points.
CloudFile read_cloud_file(const std::filesystem::path& path);

enum class PlyEncoding { binary, ascii };

/// Writes a cloud in the format its extension names (output_format.hpp; UsageError for any other): PLY
/// (binary little-endian by default) or PCD (binary) with normals when present and every attribute as an
/// `int` or `float` property/field; .vtp with normals and every attribute as a point array; .xyz with points
/// and normals only. Written as atomic_file.hpp says. UsageError for attribute sizes that do not match.
void write_cloud(const std::filesystem::path& path, const core::Cloud& cloud, const PointAttributes& attributes = {},
                 PlyEncoding encoding = PlyEncoding::binary);

/// write_cloud() for a path that must name a PLY file (UsageError otherwise).
void write_cloud_ply(const std::filesystem::path& path, const core::Cloud& cloud,
                     const PointAttributes& attributes = {}, bool binary = true);

}  // namespace partreg::io
