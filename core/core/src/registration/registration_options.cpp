#include "partreg/core/registration/registration_options.hpp"

#include <cmath>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "options/option_builders.hpp"
#include "partreg/core/geometry/part_selection.hpp"

namespace partreg::core {
namespace {

using Make = detail::OptionOn<RegistrationSettings>;
using detail::finite_vector;
using detail::vector_text;

RegistrationOption up_axis() {
  return {"up",
          "X,Y,Z",
          "the category's up axis (canonical frame); restarts turn about it; 'model': the model's own, "
          "from train --up",
          false,
          [](RegistrationSettings& s, const std::string& v) {
            if (v == "model") return s.initialisation.up.reset();
            s.initialisation.up = detail::up_axis_in(v);
          },
          [](const RegistrationSettings& s) {
            return s.initialisation.up ? vector_text(*s.initialisation.up) : std::string("model");
          }};
}

RegistrationOption seam_weight() {
  return {"seam-weight",
          "X|model",
          "coupled: weight of the mean squared gap between parts at their seams (normalised length squared); "
          "'model': the one training chose for the category",
          false,
          [](RegistrationSettings& s, const std::string& v) {
            if (v == "model") return s.objective.seam_weight.reset();
            s.objective.seam_weight = detail::real_in(v, "seam-weight", 0.0, 1e6);
          },
          [](const RegistrationSettings& s) {
            return s.objective.seam_weight ? detail::text_of(*s.objective.seam_weight) : std::string("model");
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
      Make::choice<Variant>(
          "variant", "which shape spaces are fitted", [](auto& s) -> auto& { return s.variant; }),
      Make::choice<Direction>(
          "direction", "closest points summed over: canonical (Eq. 3), observed or both",
          [](auto& s) -> auto& { return s.objective.direction; }),
      Make::choice<Loss>(
          "loss", "robust loss on each closest-point distance",
          [](auto& s) -> auto& { return s.objective.loss; }),
      Make::real(
          "loss-scale", "Huber/Cauchy scale (normalised length: the model's diagonal is 1)", 1e-6, 10.0,
          [](auto& s) -> auto& { return s.objective.loss_scale; }),
      Make::real(
          "trim", "trimmed loss: share of the worst correspondences dropped each step", 0.0, 0.9,
          [](auto& s) -> auto& { return s.objective.trim_fraction; }),
      Make::real(
          "prior-weight", "weight of the latent's Gaussian prior against the data term", 0.0, 1e6,
          [](auto& s) -> auto& { return s.objective.prior_weight; }),
      Make::real(
          "partwise-prior-weight",
          "partwise: weight of each part's latent prior (a part alone from the category frame needs more)",
          0.0, 1e6, [](auto& s) -> auto& { return s.objective.partwise_prior_weight; }),
      Make::real(
          "offset-weight",
          "coupled: weight of the prior keeping each part's rigid offset near zero, per squared normalised "
          "length it moves the part",
          0.0, 1e6, [](auto& s) -> auto& { return s.objective.offset_weight; }),
      seam_weight(),
      Make::real(
          "seam-radius",
          "coupled: canonical points this close to another part's are seam points (normalised length)", 0.0,
          1.0, [](auto& s) -> auto& { return s.objective.seam_radius; }),
      Make::real(
          "mixture-noise",
          "an observation noisier than this (normalised length) ends each space fit with EM over a Gaussian "
          "mixture instead of closest points (0: always)",
          0.0, 1e6, [](auto& s) -> auto& { return s.objective.mixture_noise; }),
      Make::flag(
          "scale", "also fit a uniform scale, within scale-limit",
          [](auto& s) -> auto& { return s.objective.estimate_scale; }),
      Make::real(
          "scale-limit",
          "with --scale, the fitted scale stays within [1/X, X] of the model's size (a fit at a bound is "
          "named in the verdict)",
          1.0, 100.0, [](auto& s) -> auto& { return s.objective.scale_limit; }),
      viewpoint(),
      Make::whole(
          "restarts", "initial rotations about the up axis, evenly spaced", 1, 360,
          [](auto& s) -> auto& { return s.initialisation.restarts; }),
      Make::flag(
          "align-axes", "also start from the rotations aligning principal axes (poses far off)",
          [](auto& s) -> auto& { return s.initialisation.align_principal_axes; }),
      Make::real(
          "max-tilt", "tilts of the up axis tried, up to this (radians)", 0.0, M_PI,
          [](auto& s) -> auto& { return s.initialisation.max_tilt; }),
      Make::flag(
          "any-rotation", "an unknown up axis: starting rotations spread over SO(3)",
          [](auto& s) -> auto& { return s.initialisation.any_rotation; }),
      up_axis(),
      Make::whole(
          "screening-iterations", "outer steps every pose hypothesis gets before the first cut", 1, 1000,
          [](auto& s) -> auto& { return s.initialisation.screening_iterations; }),
      Make::whole(
          "screening-points",
          "canonical and observed points the screening rounds match (farthest-point subsets; 0 = all)", 0,
          1000000, [](auto& s) -> auto& { return s.initialisation.screening_points; }),
      Make::whole(
          "survivors",
          "pose hypotheses screened after the cheapest look (rigid steps on the screening points; 0 = all)", 0,
          100000, [](auto& s) -> auto& { return s.initialisation.survivors; }),
      Make::whole(
          "finalists", "pose hypotheses run to convergence", 1, 10000,
          [](auto& s) -> auto& { return s.initialisation.finalists; }),
      Make::choice<SelectionScore>(
          "score", "what picks the winning pose hypothesis",
          [](auto& s) -> auto& { return s.initialisation.score; }),
      Make::real(
          "warm-limit",
          "a warm start (--init) holds while its fit's symmetric selection score stays below this "
          "(normalised length); above it the pose search runs",
          0.0, 1e6, [](auto& s) -> auto& { return s.initialisation.warm_limit; }),
      Make::real(
          "free-space-weight",
          "with a depth image, a pose hypothesis's score is multiplied by 1 + X times the share of its "
          "points in front of the measured depth (0: free space does not score)",
          0.0, 1e6, [](auto& s) -> auto& { return s.initialisation.free_space_weight; }),
      Make::whole(
          "iterations", "correspondence refreshes per space at most", 1, 10000,
          [](auto& s) -> auto& { return s.convergence.outer_iterations; }),
      Make::whole(
          "inner-iterations", "Ceres iterations per refresh", 1, 1000,
          [](auto& s) -> auto& { return s.convergence.inner_iterations; }),
      Make::real(
          "tolerance", "stop when the cost changes by less than this, relatively", 0.0, 1.0,
          [](auto& s) -> auto& { return s.convergence.tolerance; }),
      Make::whole(
          "observed-points", "farthest-point subset of the observation matched each step", 10, 10000000,
          [](auto& s) -> auto& { return s.sampling.observed_points; }),
      Make::real(
          "voxel-size", "voxel pre-pass before the farthest-point subset (normalised length; 0 = none)", 0.0,
          1.0, [](auto& s) -> auto& { return s.sampling.voxel_size; }),
      Make::real(
          "stray-limit",
          "an observed point whose 2nd neighbour is this many times the median away is matched only near the "
          "fit",
          0.0, 1000.0, [](auto& s) -> auto& { return s.sampling.stray_limit; }),
      Make::flag(
          "refine", "a non-rigid fit beyond the shape space where the observation was seen",
          [](auto& s) -> auto& { return s.refinement.enabled; }),
      Make::real(
          "refine-beta", "width of the refinement's kernel (normalised length): the finest detail", 0.005,
          1.0, [](auto& s) -> auto& { return s.refinement.beta; }),
      Make::real(
          "refine-lambda", "smoothness of the refinement's field against the data", 1e-6, 1e6,
          [](auto& s) -> auto& { return s.refinement.lambda; }),
      Make::real(
          "refine-anchor", "pull of unobserved points back to the space's shape (1: as firm as data)", 0.0,
          1e6, [](auto& s) -> auto& { return s.refinement.anchor; }),
      Make::real(
          "refine-gate", "a point farther than this from the observation is unobserved (normalised length)",
          1e-4, 10.0, [](auto& s) -> auto& { return s.refinement.gate; }),
      Make::real(
          "refine-outliers",
          "least share of the observation the refinement explains as uniform noise (the share of strays "
          "raises it)",
          0.0, 0.99, [](auto& s) -> auto& { return s.refinement.outlier_weight; }),
      Make::whole(
          "refine-iterations", "refinement EM iterations at most", 1, 1000,
          [](auto& s) -> auto& { return s.refinement.iterations; }),
      Make::real(
          "refine-noise-width",
          "the refinement's kernel is at least this many times the observation's noise wide (0 = always "
          "refine-beta)",
          0.0, 100.0, [](auto& s) -> auto& { return s.refinement.noise_width; }),
  };
}

}  // namespace

const std::vector<RegistrationOption>& registration_options() {
  static const std::vector<RegistrationOption> options = make_options();
  return options;
}

const RegistrationOption& registration_option(const std::string& name) {
  return find_option(registration_options(), name, "registration");
}

void set_registration_option(RegistrationSettings& settings, const std::string& name,
                             const std::string& value) {
  registration_option(name).set(settings, value);
}

std::vector<std::pair<std::string, std::string>> registration_option_values(
    const RegistrationSettings& settings) {
  return option_values(registration_options(), settings);
}

void validate(const RegistrationSettings& settings) {
  check_options(registration_options(), settings);
  validate(settings.verdict);
  if (settings.free_space) settings.free_space->validate();
}

}  // namespace partreg::core
