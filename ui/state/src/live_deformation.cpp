#include "partreg/ui/live_deformation.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/gaussian_kernel.hpp"

namespace partreg::ui {

LiveDeformation::LiveDeformation(const core::CategoryModel* model)
    : model_(model), caches_(model ? model->spaces.size() : 0) {}

void LiveDeformation::prepare(int space_index) {
  SpaceCache& cache = caches_[static_cast<std::size_t>(space_index)];
  if (cache.ready) return;
  const core::CategoryModel& model = *model_;
  const core::ShapeSpace& space = model.spaces[static_cast<std::size_t>(space_index)];
  const core::Mesh& mesh = model.canonical_mesh;
  cache.vertices.clear();
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    if (space_index == 0 || (model.mesh_vertex_part.size() == mesh.vertices.rows() &&
                             model.mesh_vertex_part[v] == space_index - 1))
      cache.vertices.push_back(static_cast<int>(v));
  core::Points queries(static_cast<Eigen::Index>(cache.vertices.size()), 3);
  for (std::size_t i = 0; i < cache.vertices.size(); ++i)
    queries.row(static_cast<Eigen::Index>(i)) = mesh.vertices.row(cache.vertices[i]);
  // All the weight fields side by side (M x 3(q+1)): one kernel pass gives G(V, C) W for each of them.
  const int q = space.dimensions();
  const Eigen::Index m = space.point_count();
  Eigen::MatrixXd weights(m, 3 * (q + 1));
  for (Eigen::Index row = 0; row < m; ++row)
    for (int c = 0; c < 3; ++c) {
      weights(row, c) = space.mean[3 * row + c];
      for (int k = 0; k < q; ++k) weights(row, 3 * (k + 1) + c) = space.basis(3 * row + c, k);
    }
  const Eigen::MatrixXd moved = queries.rows() > 0
                                    ? core::apply_kernel(queries, space.canonical, weights, space.beta)
                                    : Eigen::MatrixXd(0, weights.cols());
  cache.mean = moved.leftCols(3);
  cache.per_latent.resize(3 * queries.rows(), q);
  for (Eigen::Index v = 0; v < queries.rows(); ++v)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < q; ++k) cache.per_latent(3 * v + c, k) = moved(v, 3 * (k + 1) + c);
  cache.ready = true;
}

core::Points LiveDeformation::deform(const std::vector<Eigen::VectorXd>& latents, bool holistic) {
  if (!model_) return {};
  core::Points vertices = model_->canonical_mesh.vertices;
  const int spaces = static_cast<int>(model_->spaces.size());
  for (int s = holistic ? 0 : 1; s < (holistic ? 1 : spaces); ++s) {
    prepare(s);
    const SpaceCache& cache = caches_[static_cast<std::size_t>(s)];
    const Eigen::VectorXd& latent = latents.at(static_cast<std::size_t>(s));
    if (latent.size() != cache.per_latent.cols()) throw UsageError("a latent of the wrong length");
    const Eigen::VectorXd offsets = cache.per_latent * latent;
    for (std::size_t i = 0; i < cache.vertices.size(); ++i) {
      const Eigen::Index v = static_cast<Eigen::Index>(i);
      for (int c = 0; c < 3; ++c) vertices(cache.vertices[i], c) += cache.mean(v, c) + offsets[3 * v + c];
    }
  }
  return vertices;
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
