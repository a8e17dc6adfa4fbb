// The library in ten lines: load a model, register a cloud, deform the mesh, transfer a grasp frame.
// Built and run by ctest (label `cli`): partreg_library_example MODEL OBSERVED OUT_MESH.obj
#include <iostream>

#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return 2;
  using namespace partreg;
  const core::CategoryModel model = io::read_model(argv[1]);
  const core::Points observed = io::read_as_cloud(argv[2], 2000, /*seed=*/1).points;
  core::RegistrationSettings settings;
  settings.variant = model.has_parts() ? core::Variant::hol_part : core::Variant::holistic;
  const core::RegistrationResult result = core::register_observation(model, observed, settings);
  io::write_mesh(argv[3], core::deform_mesh(model, result));
  core::Frame grasp;  // a grasp pose labelled once on the canonical, in the category's frame
  grasp.position = model.normalization.undo(model.canonical.topRows(1)).row(0).transpose();
  const core::Frame moved = core::transfer_frames(model, result, {grasp}).front();
  std::cout << "fit " << result.fit.mean_normalised << " of the diagonal; grasp at "
            << moved.position.transpose() << '\n';
  return result.fit.mean_normalised < 0.05 ? 0 : 1;
}
