#include "partreg/core/registration/space_walk.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"

namespace partreg::core {
namespace {

std::vector<int> taking_part(const CategoryModel& model, bool holistic) {
  if (!holistic && !model.has_parts())
    throw UsageError("model '" + model.category + "' has no parts: walk its holistic space");
  std::vector<int> spaces;
  for (int s = holistic ? 0 : 1; s < (holistic ? 1 : static_cast<int>(model.spaces.size())); ++s)
    spaces.push_back(s);
  return spaces;
}

// Mean and basis fields of a space side by side (M x 3(q+1)): one kernel pass moves points by all of them.
Eigen::MatrixXd stacked_fields(const ShapeSpace& space) {
  const int q = space.dimensions();
  Eigen::MatrixXd fields(space.point_count(), 3 * (q + 1));
  for (Eigen::Index row = 0; row < space.point_count(); ++row)
    for (int c = 0; c < 3; ++c) {
      fields(row, c) = space.mean[3 * row + c];
      for (int k = 0; k < q; ++k) fields(row, 3 * (k + 1) + c) = space.basis(3 * row + c, k);
    }
  return fields;
}

}  // namespace

SpaceWalk::SpaceWalk(const CategoryModel& model, const Points& normalised, bool holistic,
                     const SeamBlend& blend)
    : points_(normalised) {
  const std::vector<int> spaces = taking_part(model, holistic);
  std::vector<const ShapeSpace*> blended;
  for (int s : spaces) blended.push_back(&model.spaces[static_cast<std::size_t>(s)]);
  const Eigen::MatrixXd weights = seam_weights(blended, normalised, blend);
  for (std::size_t j = 0; j < spaces.size(); ++j) {
    const ShapeSpace& space = *blended[j];
    Term term;
    term.space = spaces[j];
    for (Eigen::Index i = 0; i < normalised.rows(); ++i)
      if (weights(i, static_cast<Eigen::Index>(j)) > 0.0) term.rows.push_back(static_cast<int>(i));
    const auto rows = static_cast<Eigen::Index>(term.rows.size());
    term.weight = weights.col(static_cast<Eigen::Index>(j))(term.rows);
    const int q = space.dimensions();
    Points queries(rows, 3);
    for (Eigen::Index i = 0; i < rows; ++i)
      queries.row(i) = normalised.row(term.rows[static_cast<std::size_t>(i)]);
    const Eigen::MatrixXd moved =
        rows > 0 ? apply_kernel(queries, space.canonical, stacked_fields(space), space.beta)
                 : Eigen::MatrixXd(0, 3 * (q + 1));
    term.mean = term.weight.asDiagonal() * moved.leftCols(3);
    term.per_latent.resize(3 * rows, q);
    for (Eigen::Index i = 0; i < rows; ++i)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < q; ++k)
          term.per_latent(3 * i + c, k) = term.weight[i] * moved(i, 3 * (k + 1) + c);
    terms_.push_back(std::move(term));
  }
}

Points SpaceWalk::deform(const std::vector<Eigen::VectorXd>& latents) const {
  Points moved = points_;
  for (const Term& term : terms_) {
    const Eigen::VectorXd& latent = latents.at(static_cast<std::size_t>(term.space));
    if (latent.size() != term.per_latent.cols())
      throw UsageError("a latent of length " + std::to_string(latent.size()) + " for a space of " +
                       std::to_string(term.per_latent.cols()) + " dimensions");
    const Eigen::VectorXd offsets = term.per_latent * latent;
    for (std::size_t i = 0; i < term.rows.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      for (int c = 0; c < 3; ++c) moved(term.rows[i], c) += term.mean(r, c) + offsets[3 * r + c];
    }
  }
  return moved;
}

double max_edge_stretch(const Mesh& canonical, const Points& deformed) {
  if (deformed.rows() != canonical.vertices.rows())
    throw UsageError("the deformed vertices do not match the mesh");
  double largest = 0.0;
  for (Eigen::Index f = 0; f < canonical.faces.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = canonical.faces(f, e), b = canonical.faces(f, (e + 1) % 3);
      const double before = (canonical.vertices.row(a) - canonical.vertices.row(b)).norm();
      if (before < 1e-9) continue;
      largest = std::max(largest, (deformed.row(a) - deformed.row(b)).norm() / before);
    }
  return largest;
}

std::vector<SpaceStretch> space_grid_stretch(const CategoryModel& model, const std::vector<double>& std_devs,
                                             const SeamBlend& blend) {
  if (model.canonical_mesh.faces.rows() == 0)
    throw InputError("model '" + model.category + "' has no canonical mesh to measure stretch on");
  std::vector<Eigen::VectorXd> zero;
  for (const ShapeSpace& space : model.spaces) zero.push_back(Eigen::VectorXd::Zero(space.dimensions()));
  const SpaceWalk holistic(model, model.canonical_mesh.vertices, true, blend);
  const SpaceWalk parts =
      model.has_parts() ? SpaceWalk(model, model.canonical_mesh.vertices, false, blend) : holistic;
  std::vector<SpaceStretch> figures;
  for (int s = 0; s < static_cast<int>(model.spaces.size()); ++s) {
    const ShapeSpace& space = model.spaces[static_cast<std::size_t>(s)];
    const SpaceWalk& walk = s == 0 ? holistic : parts;
    SpaceStretch figure{space.name};
    for (int k = 0; k < space.dimensions(); ++k)
      for (double sd : std_devs) {
        std::vector<Eigen::VectorXd> latents = zero;
        latents[static_cast<std::size_t>(s)][k] = sd * std::sqrt(std::max(space.variances[k], 0.0));
        const double stretch = max_edge_stretch(model.canonical_mesh, walk.deform(latents));
        if (stretch > figure.max_stretch) figure = {space.name, stretch, k, sd};
      }
    figures.push_back(figure);
  }
  return figures;
}

}  // namespace partreg::core
