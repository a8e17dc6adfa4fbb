#include "point_normals.hpp"

#include <Eigen/Eigenvalues>

#include "partreg/core/kdtree.hpp"

namespace partreg::core::detail {

Points outward_normals(const Points& points, double radius) {
  const KdTree tree(points);
  const Eigen::RowVector3d centre = points.colwise().mean();
  Points normals(points.rows(), 3);
  std::vector<std::pair<int, double>> near;
  for (Eigen::Index m = 0; m < points.rows(); ++m) {
    tree.radius(points.row(m).transpose(), radius, near);
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& [j, d2] : near) mean += points.row(j).transpose();
    mean /= static_cast<double>(std::max<std::size_t>(near.size(), 1));
    for (const auto& [j, d2] : near)
      covariance += (points.row(j).transpose() - mean) * (points.row(j) - mean.transpose());
    Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
    if (normal.dot((points.row(m) - centre).transpose()) < 0.0) normal = -normal;
    normals.row(m) = normal.transpose();
  }
  return normals;
}

}  // namespace partreg::core::detail
