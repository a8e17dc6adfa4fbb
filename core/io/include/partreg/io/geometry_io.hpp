#pragma once
/// \file
/// "Any geometry file as points": what every command that takes a cloud-or-mesh argument uses.

#include <cstdint>
#include <filesystem>

#include "partreg/core/types.hpp"

namespace partreg::io {

/// True for mesh files: OBJ, STL, OFF, glTF/GLB, ..., PLY files whose header declares faces and .vtp files
/// holding polygons. PCD, XYZ, TXT, face-less PLY and .vtp are clouds.
bool is_mesh_file(const std::filesystem::path& path);

/// A cloud file as read (NaN points dropped, counted in `dropped_non_finite` when given), or a mesh sampled
/// area-uniformly to `mesh_samples` points with `seed`.
core::Cloud read_as_cloud(const std::filesystem::path& path, std::size_t mesh_samples, std::uint64_t seed,
                          std::size_t* dropped_non_finite = nullptr);

}  // namespace partreg::io
