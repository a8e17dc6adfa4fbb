#pragma once
/// \file
/// What `register --points-out` and `--mesh-out` write (and the Python module's write functions with a
/// result): the deformed canonical with, per point or vertex, what a reader needs to use or check it, in
/// every format that carries attributes (.ply, .vtp; PCD and XYZ keep what they can, OBJ the mesh alone).

#include <filesystem>
#include <string>
#include <vector>

#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/io/cloud_io.hpp"

namespace partreg::io {

/// Per point of `points` (the deformed canonical, observed frame): `part` (index into `part_names`, which
/// come along), `residual` (distance to the closest observed point, data units) and `correspondence` (that
/// observed point's row in the observation as it was read, from 0).
PointAttributes fit_attributes(const core::Points& points, const Eigen::VectorXi& part,
                               const std::vector<std::string>& part_names, const core::Points& observed);

/// Area-weighted unit vertex normals of a triangle mesh (zero for a vertex on no face).
core::Points vertex_normals(const core::Mesh& mesh);

/// The deformed canonical points (result.deformed) with fit_attributes and, when the model has a mesh, the
/// deformed mesh's normal at each point's nearest vertex; format by extension.
void write_registered_points(const std::filesystem::path& path, const core::CategoryModel& model,
                             const core::RegistrationResult& result, const core::Points& observed);

/// The deformed canonical mesh with its vertex normals and fit_attributes of its vertices (part: the
/// model's mesh_vertex_part); format by extension. InputError for a model without a mesh.
void write_registered_mesh(const std::filesystem::path& path, const core::CategoryModel& model,
                           const core::RegistrationResult& result, const core::Points& observed);

}  // namespace partreg::io
