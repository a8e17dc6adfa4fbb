#pragma once
// OFF meshes read by partreg itself (internal to partreg_io): assimp's OFF reader trusts the header's
// counts and aborts on a file that holds fewer faces than it claims.

#include <filesystem>

#include "partreg/core/types.hpp"

namespace partreg::io::detail {

/// Reads an ASCII OFF file (OFF, COFF, NOFF, CNOFF headers; colours and normals after the coordinates are
/// ignored; polygons are fanned into triangles). InputError naming the file for a malformed header, counts
/// beyond the reading budget or the file's size, a short file, or a face index out of range.
core::Mesh read_off(const std::filesystem::path& path, std::uint64_t file_size);

}  // namespace partreg::io::detail
