#include "partreg/io/geometry_io.hpp"

#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "ply_format.hpp"
#include "vtk_io.hpp"

namespace partreg::io {

bool is_mesh_file(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".pcd" || extension == ".xyz" || extension == ".txt") return false;
  if (extension == ".vtp") return detail::read_vtp(path).faces.rows() > 0;
  if (extension != ".ply") return true;
  return detail::read_checked_ply_header(path).count_of("face") > 0;
}

core::Cloud read_as_cloud(const std::filesystem::path& path, std::size_t mesh_samples, std::uint64_t seed,
                          std::size_t* dropped_non_finite) {
  if (dropped_non_finite) *dropped_non_finite = 0;
  if (is_mesh_file(path)) return core::sample_surface(read_mesh(path), mesh_samples, seed);
  CloudFile file = read_cloud_file(path);
  if (dropped_non_finite) *dropped_non_finite = file.dropped_non_finite;
  return std::move(file.cloud);
}

}  // namespace partreg::io
