#include "partreg/core/training/training_options.hpp"

#include <sstream>

#include "options/option_builders.hpp"
#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

using Make = detail::OptionOn<TrainingSettings>;

TrainingOption up_axis() {
  return {"up",
          "X,Y,Z",
          "the category's up axis in its data frame, kept in the model (registration turns about it; z for the "
          "drills)",
          false,
          [](TrainingSettings& s, const std::string& v) { s.up = detail::up_axis_in(v); },
          [](const TrainingSettings& s) { return detail::vector_text(s.up); }};
}

TrainingOption seam_weights() {
  return {
      "seam-weights",
      "W[,W...]",
      "coupled seam weights to try on held-out training instances' views; the best is kept in the model "
      "(one weight: that one)",
      false,
      [](TrainingSettings& s, const std::string& v) {
        std::vector<double> weights;
        std::stringstream items(v);
        for (std::string item; std::getline(items, item, ',');)
          weights.push_back(detail::real_in(item, "seam-weights", 0.0, 1e6));
        if (weights.empty() || v.back() == ',')
          throw UsageError("seam-weights must be one or more numbers separated by commas, not '" + v + "'");
        s.seam_weight_candidates = weights;
      },
      [](const TrainingSettings& s) {
        std::string text;
        for (double weight : s.seam_weight_candidates)
          text += (text.empty() ? "" : ",") + detail::text_of(weight);
        return text;
      }};
}

std::vector<TrainingOption> make_options() {
  return {
      Make::whole(
          "latent", "dimensions per shape space (at most one fewer than the instances)", 1, 1000,
          [](auto& s) -> auto& { return s.latent_dimensions; }),
      Make::whole(
          "points", "canonical points M (farthest-point sample of the canonical instance)", 10, 1000000,
          [](auto& s) -> auto& { return s.canonical_points; }),
      Make::whole(
          "part-points", "floor of canonical points per part (0: none)", 0, 1000000,
          [](auto& s) -> auto& { return s.min_part_points; }),
      Make::whole(
          "target-points", "instance points each training CPD registers onto (farthest-point sample)", 10,
          1000000, [](auto& s) -> auto& { return s.target_points; }),
      Make::real(
          "seam-band",
          "band (normalised length) within which part fields are refitted to meet at seams (0: the "
          "part CPDs' own fields)",
          0.0, 1.0, [](auto& s) -> auto& { return s.seam_band; }),
      seam_weights(),
      Make::real(
          "beta", "CPD kernel width (normalised length)", 1e-3, 10.0,
          [](auto& s) -> auto& { return s.beta; }),
      Make::real(
          "lambda", "CPD smoothness weight", 1e-6, 1e6, [](auto& s) -> auto& { return s.lambda; }),
      Make::real(
          "label-beta",
          "kernel width (normalised length) of the CPD that carries part labels to the instances (0: the "
          "holistic CPD's)",
          0.0, 10.0, [](auto& s) -> auto& { return s.label_beta; }),
      Make::real(
          "outlier-weight", "CPD's outlier share w (clean sampled surfaces have few outliers)", 0.0, 0.99,
          [](auto& s) -> auto& { return s.outlier_weight; }),
      Make::whole(
          "cpd-iterations", "CPD iterations per registration at most", 1, 100000,
          [](auto& s) -> auto& { return s.max_iterations; }),
      up_axis(),
      Make::real(
          "size",
          "the category's real size, its instances' mean bounding-box diagonal in metres, kept in the model: "
          "registration then takes observations in metres (0: in the files' own units)",
          0.0, 1000.0, [](auto& s) -> auto& { return s.size; }),
  };
}

}  // namespace

const std::vector<TrainingOption>& training_options() {
  static const std::vector<TrainingOption> options = make_options();
  return options;
}

const TrainingOption& training_option(const std::string& name) {
  return find_option(training_options(), name, "training");
}

std::vector<std::pair<std::string, std::string>> training_option_values(const TrainingSettings& settings) {
  return option_values(training_options(), settings);
}

void validate(const TrainingSettings& settings) { check_options(training_options(), settings); }

}  // namespace partreg::core
