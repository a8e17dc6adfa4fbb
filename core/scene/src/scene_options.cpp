#include "partreg/scene/scene_options.hpp"

#include <cmath>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::scene {
namespace {

double number_in(const std::string& text, const std::string& name, double low, double high) {
  std::istringstream in(text);
  double value = 0;
  in >> value;
  if (!in || !in.eof() || !std::isfinite(value) || value < low || value > high) {
    std::ostringstream what;
    what << "'" << text << "' is not a number in [" << low << ", " << high << "] for " << name;
    throw UsageError(what.str());
  }
  return value;
}

std::string text_of(double value) {
  std::ostringstream out;
  out.precision(17);
  for (int digits = 1; digits <= 17; ++digits) {
    std::ostringstream trial;
    trial.precision(digits);
    trial << value;
    if (std::stod(trial.str()) == value) return trial.str();
  }
  out << value;
  return out.str();
}

template <typename Field>
SceneOption real(std::string name, std::string help, double low, double high, Field field) {
  return {name, "X", std::move(help), false,
          [=](SceneSettings& s, const std::string& v) { field(s) = number_in(v, name, low, high); },
          [=](const SceneSettings& s) { return text_of(field(s)); }};
}

template <typename Field>
SceneOption whole(std::string name, std::string help, int low, int high, Field field) {
  return {name, "N", std::move(help), false,
          [=](SceneSettings& s, const std::string& v) {
            const double x = number_in(v, name, low, high);
            if (x != std::floor(x)) throw UsageError("'" + v + "' is not a whole number for " + name);
            field(s) = static_cast<int>(x);
          },
          [=](const SceneSettings& s) { return std::to_string(field(s)); }};
}

std::vector<SceneOption> make_options() {
  return {
      real("scene-voxel", "the scene's plane and clusters are found on a voxel grid this fine (m; 0 = none)", 0,
           1, [](auto& s) -> auto& { return s.segmentation.voxel_size; }),
      real("plane-distance", "the support plane's RANSAC inlier distance (m)", 1e-5, 1,
           [](auto& s) -> auto& { return s.segmentation.plane_distance; }),
      whole("plane-iterations", "RANSAC iterations for the support plane", 1, 1000000,
            [](auto& s) -> auto& { return s.segmentation.plane_iterations; }),
      real("min-plane-share", "least share of the scene's points the support plane must hold", 0, 1,
           [](auto& s) -> auto& { return s.segmentation.min_plane_share; }),
      whole("outlier-neighbours", "statistical outlier removal: neighbours whose mean distance is judged", 1, 1000,
            [](auto& s) -> auto& { return s.segmentation.outlier_neighbours; }),
      real("outlier-deviations",
           "statistical outlier removal: beyond this many standard deviations of the mean distance", 1e-3, 100,
           [](auto& s) -> auto& { return s.segmentation.outlier_deviations; }),
      real("cluster-tolerance", "Euclidean clustering: points closer than this join one cluster (m)", 1e-5, 1,
           [](auto& s) -> auto& { return s.segmentation.cluster_tolerance; }),
      whole("min-cluster-points", "smaller clusters (voxelised points) are noise", 1, 100000000,
            [](auto& s) -> auto& { return s.segmentation.min_cluster_points; }),
      {"search-tilts", "", "also search tilts of the up axis (max-tilt) rather than turning about the table's "
                           "normal only: for an object that may lie on its side", true,
       [](SceneSettings& s, const std::string& v) {
         if (v != "true" && v != "false") throw UsageError("'" + v + "' is not true or false for search-tilts");
         s.registration.search_tilts = v == "true";
       },
       [](const SceneSettings& s) { return std::string(s.registration.search_tilts ? "true" : "false"); }},
  };
}

}  // namespace

const std::vector<SceneOption>& scene_options() {
  static const std::vector<SceneOption> options = make_options();
  return options;
}

}  // namespace partreg::scene
