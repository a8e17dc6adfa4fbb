// How the module's result and model types print: what a user checks first (sizes, the fit, why it stopped),
// in the units the attributes carry, never an address.
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bindings.hpp"
#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/registration/verdict.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/core/transfer/grasp.hpp"
#include "partreg/eval/views.hpp"

namespace partreg::python {
namespace {

namespace py = pybind11;

// `value` with `digits` significant digits (numpy's default print precision is 8; 4 reads at a glance).
std::string number(double value, int digits = 4) {
  std::ostringstream text;
  text << std::setprecision(digits) << value;
  return text.str();
}

std::string vector_text(const Eigen::VectorXd& values) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < values.size(); ++i) text += (i ? ", " : "") + number(values[i]);
  return text + "]";
}

// Sets `__repr__` of the already bound class `name` to `describe`, inside "<partreg.NAME ...>".
template <typename T, typename Describe>
void set_repr(py::module_& m, const char* name, Describe describe) {
  py::object cls = m.attr(name);
  const std::string prefix = std::string("<partreg.") + name + " ";
  py::setattr(cls, "__repr__",
              py::cpp_function([prefix, describe](const T& self) { return prefix + describe(self) + ">"; },
                               py::name("__repr__"), py::is_method(cls)));
}

std::string fit_text(const core::FitStatistics& fit) {
  return "mean " + number(fit.mean) + " (" + number(100 * fit.mean_normalised, 3) +
         "% of the diagonal), p90 " + number(fit.p90) + ", " + std::to_string(fit.strays) + " strays";
}

void registration_reprs(py::module_& m) {
  set_repr<core::FitStatistics>(m, "FitStatistics", fit_text);
  set_repr<core::SpaceFit>(m, "SpaceFit", [](const core::SpaceFit& s) {
    return s.space + ": latent " + vector_text(s.latent) + ", translation " +
           vector_text(s.T_observed_canonical.block<3, 1>(0, 3)) + ", scale " + number(s.scale) + ", " +
           std::to_string(s.iterations) + " iterations (" + std::string(core::enum_name(s.stop_reason)) + ")";
  });
  set_repr<core::HistoryStep>(m, "HistoryStep", [](const core::HistoryStep& s) {
    return s.space + ": cost " + number(s.cost) + " at " + number(s.seconds, 3) + " s";
  });
  set_repr<core::RefinementField>(m, "Refinement", [](const core::RefinementField& s) {
    if (s.empty()) return std::string("not applied");
    return std::to_string(s.points) + " points (" + std::to_string(s.observed) + " observed), " +
           std::to_string(s.iterations) + " iterations, mean movement " + number(s.mean_movement) +
           " of the diagonal";
  });
  set_repr<core::MixtureFinish>(m, "MixtureFinish", [](const core::MixtureFinish& s) {
    return std::string(s.applied ? "applied" : "not applied") + ", noise " + number(s.noise) + ", sigma " +
           number(s.sigma);
  });
  set_repr<core::TrustFigures>(m, "TrustFigures", [](const core::TrustFigures& f) {
    return "inliers " + number(100 * f.inlier_share, 3) + "%, observed rms " + number(100 * f.observed_rms, 3) +
           "% of the diagonal, latent distance " + number(f.latent_distance, 3) + ", pose ambiguity " +
           number(f.pose_ambiguity, 3) + ", stretch " + number(f.mesh_stretch, 3) + ", scale " + number(f.scale) +
           (f.free_space_violation ? ", free-space violation " + number(100 * *f.free_space_violation, 3) + "%"
                                   : std::string());
  });
  set_repr<core::RegistrationResult>(m, "RegistrationResult", [](const core::RegistrationResult& s) {
    std::string spaces;
    for (const core::SpaceFit& fit : s.fits) spaces += (spaces.empty() ? "" : ", ") + fit.space;
    return std::string(core::enum_name(s.variant)) + ": " + std::to_string(s.deformed.rows()) +
           " points, spaces [" + spaces + "], verdict " + std::string(core::enum_name(s.assessment.verdict)) +
           ", fit " + fit_text(s.fit) + ", " + number(s.seconds, 3) + " s";
  });
}

template <typename Result>
std::string cpd_text(const Result& s) {
  return std::to_string(s.moved.rows()) + " points, " + std::to_string(s.iterations) + " iterations (" +
         core::to_string(s.stop_reason) + "), sigma2 " + number(s.sigma2) + ", " + number(s.seconds, 3) +
         " s";
}

void cpd_reprs(py::module_& m) {
  set_repr<core::RigidCpdResult>(m, "RigidCpdResult", [](const core::RigidCpdResult& s) {
    const double angle = Eigen::AngleAxisd(s.rotation).angle() * 180.0 / M_PI;
    return cpd_text(s) + ", rotation " + number(angle) + " deg, translation " + vector_text(s.translation) +
           ", scale " + number(s.scale);
  });
  set_repr<core::AffineCpdResult>(m, "AffineCpdResult", [](const core::AffineCpdResult& s) {
    return cpd_text(s) + ", translation " + vector_text(s.translation);
  });
  set_repr<core::NonrigidCpdResult>(m, "NonrigidCpdResult", [](const core::NonrigidCpdResult& s) {
    return cpd_text(s) + ", beta " + number(s.beta) + ", kernel rank " + std::to_string(s.kernel_rank);
  });
}

}  // namespace

void bind_reprs(py::module_& m) {
  set_repr<core::Frame>(m, "Frame", [](const core::Frame& f) {
    const double angle = Eigen::AngleAxisd(f.rotation).angle() * 180.0 / M_PI;
    return f.name + " at " + vector_text(f.position) + ", rotated " + number(angle) + " deg";
  });
  set_repr<eval::View>(m, "View", [](const eval::View& s) {
    return std::to_string(s.points.rows()) + " points from " + vector_text(s.viewpoint);
  });
  set_repr<core::Gripper>(m, "Gripper", [](const core::Gripper& g) {
    return "aperture " + number(g.max_aperture) + ", pad " + number(g.pad_size) + ", depth " +
           number(g.finger_depth) + ", mu " + number(g.friction) + (g.relative ? " (fractions of the diagonal)" : "");
  });
  set_repr<core::Grasp>(m, "Grasp", [](const core::Grasp& g) {
    return g.name + (g.part.empty() ? "" : " on " + g.part) + " at " + vector_text(g.position) + ", width " +
           number(g.width) + ", quality " + number(g.quality);
  });
  registration_reprs(m);
  cpd_reprs(m);
}

}  // namespace partreg::python
