// How often the pose search keeps the right hypothesis: leave-one-out on real categories, each held-out
// instance seen fully and from one partial view, turned about its up axis. For every observation the
// truth-best hypothesis is found by brute force (a single start at each of the search's yaws, scored against
// the truth); each selection score then runs the search and we count how often its result is within 10% of
// that best. Not a test: it prints the figures behind docs/pose_search.md. Run (a few minutes):
//   ./build/tests/bench/pose_selection_study [folder ...] [NAME=VALUE ...]   (default: mugs bowls kettles)
// NAME=VALUE sets a registration option of the search (e.g. finalists=4) and of the single starts the
// truth-best is taken from (whose restarts and tilts are always 1 and none); score=S studies that score only.
#include <cstdio>
#include <map>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/eval/views.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"

namespace {

using namespace partreg;

struct Observation {
  core::Points points;
  std::optional<Eigen::Vector3d> viewpoint;
  core::Points truth;  // the whole instance, in the observation's frame
};

core::Points turned(const core::Points& points, const Eigen::Matrix3d& R) { return points * R.transpose(); }

std::vector<Observation> observations(const core::TrainingInstance& instance) {
  std::vector<Observation> out;
  const eval::ViewCaster caster =
      instance.mesh.faces.rows() ? eval::ViewCaster(instance.mesh) : eval::ViewCaster(instance.points);
  const eval::View side = caster.cast(Eigen::Vector3d(1, 0.5, 1).normalized());
  for (double yaw_deg : {0.0, 90.0, 180.0, 270.0}) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    out.push_back({turned(instance.points, R), std::nullopt, turned(instance.points, R)});
    out.push_back({turned(side.points, R), R * side.viewpoint, turned(instance.points, R)});
  }
  return out;
}

double true_error(const core::RegistrationResult& result, const Observation& seen, double diagonal) {
  return core::measure_against_truth(result.deformed, result.part, {}, seen.truth, diagonal)
      .symmetric_rms_per_diagonal;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> folders;
  std::vector<std::pair<std::string, std::string>> options;  // applied to every search
  std::vector<std::string> scores = core::enum_names<core::SelectionScore>();
  for (int a = 1; a < argc; ++a) {
    const std::string argument = argv[a];
    const std::size_t equals = argument.find('=');
    if (equals == std::string::npos) {
      folders.push_back(argument);
    } else if (argument.substr(0, equals) == "score") {
      scores = {argument.substr(equals + 1)};
    } else {
      options.emplace_back(argument.substr(0, equals), argument.substr(equals + 1));
    }
  }
  if (folders.empty()) folders = {"mugs", "bowls", "kettles"};
  const int yaws = 12;
  std::map<std::string, std::pair<int, int>> agree;  // score -> (within 10%, cases)
  std::map<std::string, double> error_sum;
  double best_sum = 0.0, single_sum = 0.0;
  int single_agree = 0, cases = 0;
  for (const std::string& folder : folders) {
    const auto path = testing::shared_data(folder);
    if (!std::filesystem::exists(path)) {
      std::printf("skipped %s: shared data absent\n", folder.c_str());
      continue;
    }
    const io::Dataset dataset = io::read_dataset(path);
    for (std::size_t held = 0; held < dataset.instances.size(); ++held) {
      std::vector<core::TrainingInstance> training = dataset.instances;
      training.erase(training.begin() + static_cast<long>(held));
      const core::CategoryModel model = core::train_category(dataset.name, training, dataset.part_names, {});
      const double diagonal = core::truth_diagonal(dataset.instances[held].points);
      for (const Observation& seen : observations(dataset.instances[held])) {
        double best = 1e9, single = 0.0;
        for (int k = 0; k < yaws; ++k) {  // the hypothesis at yaw k, alone: turn the observation instead
          const Eigen::Matrix3d R =
              Eigen::AngleAxisd(-2.0 * M_PI * k / yaws, Eigen::Vector3d::UnitY()).toRotationMatrix();
          core::RegistrationSettings one;
          for (const auto& [name, value] : options) core::set_registration_option(one, name, value);
          // One start, whatever the search's defaults: yaw k is the observation's turn, no tilt.
          core::set_registration_option(one, "restarts", "1");
          core::set_registration_option(one, "max-tilt", "0");
          if (seen.viewpoint) one.viewpoint = R * *seen.viewpoint;
          Observation moved{turned(seen.points, R), one.viewpoint, turned(seen.truth, R)};
          const double e = true_error(core::register_observation(model, moved.points, one), moved, diagonal);
          best = std::min(best, e);
          if (k == 0) single = e;
        }
        best_sum += best, single_sum += single, ++cases;
        single_agree += single <= 1.1 * best;
        for (const std::string& score : scores) {
          core::RegistrationSettings search;
          search.viewpoint = seen.viewpoint;
          core::set_registration_option(search, "restarts", std::to_string(yaws));
          core::set_registration_option(search, "score", score);
          for (const auto& [name, value] : options) core::set_registration_option(search, name, value);
          const double e = true_error(core::register_observation(model, seen.points, search), seen, diagonal);
          agree[score].first += e <= 1.1 * best;
          ++agree[score].second;
          error_sum[score] += e;
        }
      }
      std::fprintf(stderr, "%s %zu/%zu done\n", folder.c_str(), held + 1, dataset.instances.size());
    }
  }
  std::printf("| score | kept within 10%% of the truth-best | mean symmetric RMS |\n|---|---|---|\n");
  std::printf("| (one start, no search) | %.0f%% | %.4f |\n", 100.0 * single_agree / std::max(cases, 1),
              single_sum / std::max(cases, 1));
  for (const std::string& score : scores)
    std::printf("| %s | %.0f%% | %.4f |\n", score.c_str(), 100.0 * agree[score].first / std::max(cases, 1),
                error_sum[score] / std::max(cases, 1));
  std::printf("| (truth-best of %d yaws) | 100%% | %.4f |\n", yaws, best_sum / std::max(cases, 1));
  std::printf("%d observations\n", cases);
  return 0;
}
