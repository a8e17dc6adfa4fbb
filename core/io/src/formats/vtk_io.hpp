#pragma once
// ParaView's PolyData files (.vtp) through VTK, kept in one translation unit (internal to partreg_io). VTK
// only reads and writes files here: it is not the renderer (docs/rendering.md says why).

#include <filesystem>
#include <ostream>

#include "partreg/core/types.hpp"
#include "partreg/io/cloud_io.hpp"

namespace partreg::io::detail {

/// What a .vtp file holds for partreg: points, their normals (when present), triangles (polygons are
/// fanned; vertex and line cells ignored), every one-component point array as an attribute, and the
/// field-data string array `part_names` as the attributes' part names.
struct PolyData {
  core::Points points;
  core::Points normals;
  core::Faces faces;
  PointAttributes attributes;
};

/// Reads a .vtp file (checked against the reading budget). InputError naming the file for anything VTK
/// cannot read or that refers to points that do not exist.
PolyData read_vtp(const std::filesystem::path& path);

/// Writes `data` as an XML PolyData file to `out` (binary, zlib-compressed arrays). A cloud (no faces) gets
/// one vertex cell per point so ParaView shows it; normals go to the point data's Normals; integer
/// attributes as Int32 arrays and real ones as Float64 arrays.
void write_vtp(std::ostream& out, const PolyData& data);

}  // namespace partreg::io::detail
