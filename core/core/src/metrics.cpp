#include "partreg/core/metrics.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/kdtree.hpp"

namespace partreg::core {
namespace {

Eigen::VectorXd squared_to_closest(const Points& from, const Points& to) {
  if (from.rows() == 0 || to.rows() == 0) throw InputError("cannot measure an error with an empty point set");
  const KdTree tree(to);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(from, index, squared);
  return squared;
}

}  // namespace

double closest_point_error(const Points& deformed, const Points& truth) {
  return squared_to_closest(deformed, truth).mean();
}

double chamfer_distance(const Points& a, const Points& b) {
  return 0.5 * (squared_to_closest(a, b).cwiseSqrt().mean() + squared_to_closest(b, a).cwiseSqrt().mean());
}

}  // namespace partreg::core
