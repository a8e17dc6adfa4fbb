#include "partreg/core/space/shape_space.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"

namespace partreg::core {
namespace {

Points random_points(int count, std::mt19937_64& generator) {
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Points points(count, 3);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = uniform(generator);
  return points;
}

// K weight fields spread along `rank` fixed directions with decreasing spread, plus a little noise.
std::vector<Points> low_rank_fields(int m, int count, int rank, std::mt19937_64& generator) {
  std::normal_distribution<double> normal;
  std::vector<Points> directions;
  for (int k = 0; k < rank; ++k) directions.push_back(random_points(m, generator));
  std::vector<Points> fields;
  for (int i = 0; i < count; ++i) {
    Points field = Points::Constant(m, 3, 0.01);
    for (int k = 0; k < rank; ++k)
      field += (normal(generator) / (1 + k)) * directions[static_cast<std::size_t>(k)];
    for (Eigen::Index j = 0; j < field.size(); ++j) field.data()[j] += 1e-4 * normal(generator);
    fields.push_back(field);
  }
  return fields;
}

std::vector<int> iota(int count) {
  std::vector<int> indices(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) indices[static_cast<std::size_t>(i)] = i;
  return indices;
}

double reconstruction_error(const ShapeSpace& space, const std::vector<Points>& fields) {
  double error = 0.0;
  for (const Points& field : fields)
    error += (space.weights(space.project_weights(field)) - field).squaredNorm();
  return error;
}

TEST(PcaEm, BasisIsOrthonormalAndVariancesDescend) {
  std::mt19937_64 generator(3);
  const Points canonical = random_points(200, generator);
  const auto fields = low_rank_fields(200, 9, 4, generator);
  const ShapeSpace space = learn_shape_space("holistic", iota(200), canonical, 0.3, fields, {});
  ASSERT_EQ(space.dimensions(), 5);
  const Eigen::MatrixXd gram = space.kernel_basis.transpose() * space.kernel_basis;
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-9);
  for (int k = 1; k < space.dimensions(); ++k) EXPECT_GE(space.variances[k - 1], space.variances[k]);
  EXPECT_GT(space.explained_fraction().head(4).sum(), 0.99);  // four true directions carry nearly everything
}

TEST(PcaEm, AgreesWithThePrincipalSubspaceOfAnSvd) {
  std::mt19937_64 generator(5);
  const auto fields = low_rank_fields(150, 8, 6, generator);
  Eigen::MatrixXd data(450, 8);
  for (int i = 0; i < 8; ++i)
    data.col(i) = Eigen::Map<const Eigen::VectorXd>(fields[static_cast<std::size_t>(i)].data(), 450);
  const Eigen::MatrixXd centred = data.colwise() - data.rowwise().mean();
  Eigen::VectorXd variances;
  PcaEmSettings settings;
  settings.dimensions = 3;
  const Eigen::MatrixXd basis = pca_em(centred, settings, variances);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinU);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(std::abs(basis.col(k).dot(svd.matrixU().col(k))), 1.0, 1e-6) << "component " << k;
    EXPECT_NEAR(variances[k], svd.singularValues()[k] * svd.singularValues()[k] / 7.0, 1e-6 * variances[0]);
  }
}

TEST(ShapeSpace, ReconstructionErrorFallsAsDimensionsGrow) {
  std::mt19937_64 generator(7);
  const Points canonical = random_points(120, generator);
  const auto fields = low_rank_fields(120, 10, 6, generator);
  double previous = std::numeric_limits<double>::infinity();
  for (int q = 1; q <= 6; ++q) {
    PcaEmSettings settings;
    settings.dimensions = q;
    const double error =
        reconstruction_error(learn_shape_space("h", iota(120), canonical, 0.3, fields, settings), fields);
    EXPECT_LT(error, previous) << "q = " << q;
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);  // six true directions: q = 6 leaves only the noise
}

TEST(ShapeSpace, DeformedMatchesTheKernelAppliedToTheWeights) {
  std::mt19937_64 generator(11);
  const Points canonical = random_points(80, generator);
  const auto fields = low_rank_fields(80, 6, 3, generator);
  const ShapeSpace space = learn_shape_space("h", iota(80), canonical, 0.25, fields, {});
  Eigen::VectorXd latent = Eigen::VectorXd::LinSpaced(space.dimensions(), -1.0, 1.0);
  const Points direct = canonical + gaussian_kernel(canonical, canonical, 0.25) * space.weights(latent);
  // kernel_basis comes from the PCA and basis from the same combination of the fields: equal up to round-off.
  EXPECT_LT((space.deformed(latent) - direct).cwiseAbs().maxCoeff(), 1e-7);
  // project_displacement inverts deformed(): the latent comes back.
  EXPECT_LT((space.project_displacement(space.deformed(latent) - canonical) - latent).norm(), 1e-6);
}

TEST(ShapeSpace, RefusesTooFewOrMismatchedFields) {
  std::mt19937_64 generator(13);
  const Points canonical = random_points(30, generator);
  EXPECT_THROW(learn_shape_space("h", iota(30), canonical, 0.3, {Points::Zero(30, 3)}, {}), InputError);
  EXPECT_THROW(
      learn_shape_space("h", iota(30), canonical, 0.3, {Points::Zero(30, 3), Points::Zero(29, 3)}, {}),
      InputError);
}

}  // namespace
}  // namespace partreg::core
