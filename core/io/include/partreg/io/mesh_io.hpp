#pragma once
/// \file
/// Triangle meshes: reading every format assimp reads (OBJ, PLY, STL, glTF/GLB, ...; PLY headers checked by
/// partreg first, every index checked), OFF (partreg's own reader) and .vtp (VTK); writing OBJ, PLY and .vtp.

#include <Eigen/Core>
#include <filesystem>

#include "partreg/core/types.hpp"
#include "partreg/io/cloud_io.hpp"

namespace partreg::io {

/// Reads a mesh: all meshes of the file merged with their node transforms, triangulated, identical vertices
/// joined, degenerate faces dropped. Throws InputError for a missing file, a format assimp cannot read, or a
/// file without faces ("... is a point cloud"), a face referring to a vertex that does not exist, or counts
/// beyond the file's size or the reading budget (read_limits.hpp).
core::Mesh read_mesh(const std::filesystem::path& path);

/// A mesh with what its file says of each vertex.
struct MeshFile {
  core::Mesh mesh;                    ///< normals too where the file has them
  PointAttributes vertex_attributes;  ///< one value per mesh vertex, and the part names
};

/// read_mesh() with the vertices' attributes and normals of the files partreg writes: a .vtp file's point
/// arrays as stored (its vertices are not joined), a .ply file's vertex properties matched to the mesh's
/// vertices by position (none when a vertex has no match). Other formats: the mesh alone.
MeshFile read_mesh_file(const std::filesystem::path& path);

/// Writes .obj, .ply or .vtp (by extension, output_format.hpp; UsageError otherwise), as atomic_file.hpp
/// says. PLY gets an int `part` vertex property when `vertex_part` is given (one value per vertex), .vtp a
/// `part` point array.
void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh,
                const Eigen::VectorXi* vertex_part = nullptr);

/// write_mesh() with any per-vertex arrays and the part names, and the mesh's normals when it has them: all
/// of them go to .vtp and .ply files (read back by read_mesh_file); OBJ keeps none.
void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh, const PointAttributes& attributes);

}  // namespace partreg::io
