#pragma once
/// \file
/// Triangle meshes: reading every format assimp reads (OBJ, PLY, STL, OFF, glTF/GLB, ...), writing OBJ and
/// PLY.

#include <Eigen/Core>
#include <filesystem>

#include "partreg/core/types.hpp"

namespace partreg::io {

/// Reads a mesh: all meshes of the file merged with their node transforms, triangulated, identical vertices
/// joined, degenerate faces dropped. Throws InputError for a missing file, a format assimp cannot read, or a
/// file without faces ("... is a point cloud").
core::Mesh read_mesh(const std::filesystem::path& path);

/// Writes .obj or .ply (by extension; UsageError otherwise), atomically. PLY gets an int `part` vertex
/// property when `vertex_part` is given (one value per vertex).
void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh,
                const Eigen::VectorXi* vertex_part = nullptr);

}  // namespace partreg::io
