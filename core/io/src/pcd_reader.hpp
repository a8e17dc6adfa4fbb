#pragma once
// PCD reading through PCL, kept in one translation unit (internal to partreg_io).

#include <filesystem>

#include "partreg/io/cloud_io.hpp"

namespace partreg::io::detail {

/// Reads x, y, z and, when present, normal_x/y/z of any PCD encoding. NaN points are kept (the caller drops).
CloudFile read_pcd(const std::filesystem::path& path);

}  // namespace partreg::io::detail
