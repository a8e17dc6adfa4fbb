#include "partreg/core/registration_options.hpp"

#include <cmath>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/part_selection.hpp"

namespace partreg::core {
namespace {

using Setter = std::function<void(RegistrationSettings&, const std::string&)>;
using Getter = std::function<std::string(const RegistrationSettings&)>;

// The shortest text that reads back as exactly `value` (0.03, not 0.029999999999999999).
std::string text_of(double value) {
  for (int digits = 6;; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    if (digits >= 17 || std::strtod(out.str().c_str(), nullptr) == value) return out.str();
  }
}

double real_in(const std::string& text, const std::string& what, double low, double high) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw UsageError(what + " must be a number, not '" + text + "'");
  if (value < low || value > high)
    throw UsageError(what + " must be in [" + text_of(low) + ", " + text_of(high) + "], not " + text);
  return value;
}

int integer_in(const std::string& text, const std::string& what, int low, int high) {
  const double value = real_in(text, what, low, high);
  if (value != std::floor(value)) throw UsageError(what + " must be a whole number, not '" + text + "'");
  return static_cast<int>(value);
}

bool boolean(const std::string& text, const std::string& what) {
  if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
  if (text == "false" || text == "0" || text == "off" || text == "no") return false;
  throw UsageError(what + " must be true or false, not '" + text + "'");
}

Eigen::Vector3d finite_vector(const std::string& text, const std::string& what) {
  const Eigen::Vector3d v = parse_vector3(text, what);
  if (!v.allFinite()) throw UsageError(what + " must be finite, not '" + text + "'");
  return v;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return text_of(v.x()) + "," + text_of(v.y()) + "," + text_of(v.z());
}

// An option on one field: `field` picks it out of the settings.
template <typename Enum, typename Field>
RegistrationOption choice(std::string name, std::string help, Field field) {
  return {name,
          enum_choices<Enum>("|"),
          std::move(help),
          false,
          [field](RegistrationSettings& s, const std::string& v) { field(s) = parse_enum<Enum>(v); },
          [field](const RegistrationSettings& s) { return enum_name(field(s)); }};
}

template <typename Field>
RegistrationOption real(std::string name, std::string help, double low, double high, Field field) {
  return {name,
          "X",
          std::move(help),
          false,
          [=](RegistrationSettings& s, const std::string& v) { field(s) = real_in(v, name, low, high); },
          [=](const RegistrationSettings& s) { return text_of(field(s)); }};
}

template <typename Field>
RegistrationOption whole(std::string name, std::string help, int low, int high, Field field) {
  return {name,
          "N",
          std::move(help),
          false,
          [=](RegistrationSettings& s, const std::string& v) { field(s) = integer_in(v, name, low, high); },
          [=](const RegistrationSettings& s) { return std::to_string(field(s)); }};
}

template <typename Field>
RegistrationOption flag(std::string name, std::string help, Field field) {
  return {name,
          "",
          std::move(help),
          true,
          [=](RegistrationSettings& s, const std::string& v) { field(s) = boolean(v, name); },
          [=](const RegistrationSettings& s) { return std::string(field(s) ? "true" : "false"); }};
}

RegistrationOption up_axis() {
  return {"up",
          "X,Y,Z",
          "the category's up axis (canonical frame); restarts turn about it; 'model': the model's own, "
          "from train --up",
          false,
          [](RegistrationSettings& s, const std::string& v) {
            if (v == "model") return s.initialisation.up.reset();
            const Eigen::Vector3d up = finite_vector(v, "up");
            if (up.norm() < 1e-12) throw UsageError("up axis " + v + " has zero length");
            s.initialisation.up = up;
          },
          [](const RegistrationSettings& s) {
            return s.initialisation.up ? vector_text(*s.initialisation.up) : std::string("model");
          }};
}

RegistrationOption viewpoint() {
  return {"viewpoint",
          "X,Y,Z|none",
          "camera position (observed frame, data units): only canonical points facing it are matched",
          false,
          [](RegistrationSettings& s, const std::string& v) {
            if (v == "none")
              s.viewpoint.reset();
            else
              s.viewpoint = finite_vector(v, "viewpoint");
          },
          [](const RegistrationSettings& s) { return s.viewpoint ? vector_text(*s.viewpoint) : "none"; }};
}

std::vector<RegistrationOption> make_options() {
  return {
      choice<Variant>(
          "variant", "which shape spaces are fitted", [](auto& s) -> auto& { return s.variant; }),
      choice<Direction>(
          "direction", "closest points summed over: canonical (Eq. 3), observed or both",
          [](auto& s) -> auto& { return s.objective.direction; }),
      choice<Loss>(
          "loss", "robust loss on each closest-point distance",
          [](auto& s) -> auto& { return s.objective.loss; }),
      real(
          "loss-scale", "Huber/Cauchy scale (normalised length: the model's diagonal is 1)", 1e-6, 10.0,
          [](auto& s) -> auto& { return s.objective.loss_scale; }),
      real(
          "trim", "trimmed loss: share of the worst correspondences dropped each step", 0.0, 0.9,
          [](auto& s) -> auto& { return s.objective.trim_fraction; }),
      real(
          "prior-weight", "weight of the latent's Gaussian prior against the data term", 0.0, 1e6,
          [](auto& s) -> auto& { return s.objective.prior_weight; }),
      real(
          "offset-weight",
          "coupled: weight of the prior keeping each part's rigid offset near zero, per squared normalised "
          "length it moves the part",
          0.0, 1e6, [](auto& s) -> auto& { return s.objective.offset_weight; }),
      real(
          "seam-weight",
          "coupled: weight of the mean squared gap between parts at their seams (normalised length squared)",
          0.0, 1e6, [](auto& s) -> auto& { return s.objective.seam_weight; }),
      real(
          "seam-radius",
          "coupled: canonical points this close to another part's are seam points (normalised length)", 0.0,
          1.0, [](auto& s) -> auto& { return s.objective.seam_radius; }),
      flag(
          "scale", "also fit a uniform scale", [](auto& s) -> auto& { return s.objective.estimate_scale; }),
      viewpoint(),
      whole(
          "restarts", "initial rotations about the up axis, evenly spaced", 1, 360,
          [](auto& s) -> auto& { return s.initialisation.restarts; }),
      flag(
          "align-axes", "also start from the rotations aligning principal axes (poses far off)",
          [](auto& s) -> auto& { return s.initialisation.align_principal_axes; }),
      real(
          "max-tilt", "tilts of the up axis tried, up to this (radians)", 0.0, M_PI,
          [](auto& s) -> auto& { return s.initialisation.max_tilt; }),
      flag(
          "any-rotation", "an unknown up axis: starting rotations spread over SO(3)",
          [](auto& s) -> auto& { return s.initialisation.any_rotation; }),
      up_axis(),
      whole(
          "screening-iterations", "outer steps every pose hypothesis gets before the first cut", 1, 1000,
          [](auto& s) -> auto& { return s.initialisation.screening_iterations; }),
      whole(
          "screening-points",
          "canonical and observed points the screening rounds match (farthest-point subsets; 0 = all)", 0,
          1000000, [](auto& s) -> auto& { return s.initialisation.screening_points; }),
      whole(
          "finalists", "pose hypotheses run to convergence", 1, 10000,
          [](auto& s) -> auto& { return s.initialisation.finalists; }),
      choice<SelectionScore>(
          "score", "what picks the winning pose hypothesis",
          [](auto& s) -> auto& { return s.initialisation.score; }),
      whole(
          "iterations", "correspondence refreshes per space at most", 1, 10000,
          [](auto& s) -> auto& { return s.convergence.outer_iterations; }),
      whole(
          "inner-iterations", "Ceres iterations per refresh", 1, 1000,
          [](auto& s) -> auto& { return s.convergence.inner_iterations; }),
      real(
          "tolerance", "stop when the cost changes by less than this, relatively", 0.0, 1.0,
          [](auto& s) -> auto& { return s.convergence.tolerance; }),
      whole(
          "observed-points", "farthest-point subset of the observation matched each step", 10, 10000000,
          [](auto& s) -> auto& { return s.sampling.observed_points; }),
      real(
          "voxel-size", "voxel pre-pass before the farthest-point subset (normalised length; 0 = none)", 0.0,
          1.0, [](auto& s) -> auto& { return s.sampling.voxel_size; }),
      flag(
          "refine", "a non-rigid fit beyond the shape space where the observation was seen",
          [](auto& s) -> auto& { return s.refinement.enabled; }),
      real(
          "refine-beta", "width of the refinement's kernel (normalised length): the finest detail", 0.005, 1.0,
          [](auto& s) -> auto& { return s.refinement.beta; }),
      real(
          "refine-lambda", "smoothness of the refinement's field against the data", 1e-6, 1e6,
          [](auto& s) -> auto& { return s.refinement.lambda; }),
      real(
          "refine-anchor", "pull of unobserved points back to the space's shape (1: as firm as data)", 0.0, 1e6,
          [](auto& s) -> auto& { return s.refinement.anchor; }),
      real(
          "refine-gate", "a point farther than this from the observation is unobserved (normalised length)",
          1e-4, 10.0, [](auto& s) -> auto& { return s.refinement.gate; }),
      real(
          "refine-outliers", "share of the observation the refinement explains as uniform noise", 0.0, 0.99,
          [](auto& s) -> auto& { return s.refinement.outlier_weight; }),
      whole(
          "refine-iterations", "refinement EM iterations at most", 1, 1000,
          [](auto& s) -> auto& { return s.refinement.iterations; }),
      real(
          "refine-noise-limit",
          "the refinement stands down when the observed surface is thicker than this (median spread off "
          "local planes; normalised length)",
          1e-4, 10.0, [](auto& s) -> auto& { return s.refinement.noise_limit; }),
  };
}

}  // namespace

const std::vector<RegistrationOption>& registration_options() {
  static const std::vector<RegistrationOption> options = make_options();
  return options;
}

const RegistrationOption& registration_option(const std::string& name) {
  for (const RegistrationOption& option : registration_options())
    if (option.name == name) return option;
  std::string known;
  for (const RegistrationOption& option : registration_options())
    known += (known.empty() ? "" : ", ") + option.name;
  throw UsageError("unknown registration setting '" + name + "' (known: " + known + ")");
}

void set_registration_option(RegistrationSettings& settings, const std::string& name,
                             const std::string& value) {
  registration_option(name).set(settings, value);
}

std::vector<std::pair<std::string, std::string>> registration_option_values(
    const RegistrationSettings& settings) {
  std::vector<std::pair<std::string, std::string>> values;
  for (const RegistrationOption& option : registration_options())
    values.emplace_back(option.name, option.get(settings));
  return values;
}

void validate(const RegistrationSettings& settings) {
  // Each option checks its own range on the way in; settings built in code are checked here the same way.
  for (const RegistrationOption& option : registration_options()) {
    RegistrationSettings copy = settings;
    option.set(copy, option.get(settings));
  }
}

}  // namespace partreg::core
