// A study, not a benchmark: labels propagated to a held-out kettle through a registration,
// with and without the refinement. Leave-one-out over the kettles (their own part files are the truth): a
// model is trained on the others, the held-out kettle's full surface sample is registered (holistic), and
// each of its points takes the part of the nearest registered canonical point. Prints the agreement per
// held-out kettle. Run: ./build/tests/bench/label_propagation_study
#include <iostream>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"

namespace {

double agreement(const partreg::core::RegistrationResult& result, const partreg::core::TrainingInstance& truth) {
  const partreg::core::KdTree tree(result.deformed);
  int same = 0;
  for (Eigen::Index i = 0; i < truth.points.rows(); ++i)
    same += result.part[tree.nearest(truth.points.row(i).transpose()).first] == truth.part[i];
  return static_cast<double>(same) / static_cast<double>(truth.points.rows());
}

}  // namespace

int main() {
  const auto path = partreg::testing::shared_data("kettles");
  if (!std::filesystem::exists(path)) {
    std::cerr << "shared data absent: ../shared/data/kettles\n";
    return 0;
  }
  const partreg::io::Dataset dataset = partreg::io::read_dataset(path, {});
  std::cout << "| held-out kettle | space fit | refined |\n|---|---|---|\n";
  for (std::size_t held = 0; held < dataset.instances.size(); ++held) {
    std::vector<partreg::core::TrainingInstance> training;
    for (std::size_t i = 0; i < dataset.instances.size(); ++i)
      if (i != held) training.push_back(dataset.instances[i]);
    const partreg::core::CategoryModel model =
        partreg::core::train_category(dataset.name, training, dataset.part_names, {});
    const partreg::core::TrainingInstance& truth = dataset.instances[held];
    partreg::core::RegistrationSettings settings;
    settings.refinement.enabled = false;  // on by default: the first column is the space fit alone
    const double space = agreement(partreg::core::register_observation(model, truth.points, settings), truth);
    settings.refinement.enabled = true;
    const double refined = agreement(partreg::core::register_observation(model, truth.points, settings), truth);
    std::cout << "| " << truth.name << " | " << 100.0 * space << "% | " << 100.0 * refined << "% |\n";
  }
  return 0;
}
