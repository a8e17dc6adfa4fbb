#include "partreg/ui/live_deformation.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"

namespace partreg::ui {

LiveDeformation::LiveDeformation(const core::CategoryModel* model) : model_(model) {}

core::Points LiveDeformation::deform(const std::vector<Eigen::VectorXd>& latents, bool holistic) {
  if (!model_) return {};
  std::optional<core::SpaceWalk>& walk = holistic || !model_->has_parts() ? holistic_ : parts_;
  if (!walk) walk.emplace(*model_, model_->canonical_mesh.vertices, holistic || !model_->has_parts());
  return walk->deform(latents);
}

const core::Points& LiveDeformation::fitted_instance(int instance) {
  if (!model_) throw UsageError("no model is loaded");
  const auto found = instances_.find(instance);
  if (found != instances_.end()) return found->second;
  const core::CategoryModel& model = *model_;
  const core::ShapeSpace& holistic = model.holistic();
  const core::Points& start =
      model.canonical_mesh.faces.rows() > 0 ? model.canonical_mesh.vertices : model.canonical;
  const core::Points weights = model.training_weight_field(instance);
  core::Points moved =
      start + core::Points(core::apply_kernel(start, holistic.canonical, weights, holistic.beta));
  return instances_.emplace(instance, std::move(moved)).first->second;
}

}  // namespace partreg::ui
