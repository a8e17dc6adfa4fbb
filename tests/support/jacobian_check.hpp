#pragma once
// A Ceres cost's Jacobian against central differences, shared by the tests of partreg's hand-derived costs
// (the moment cost, the coupled variant's data and seam terms).
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace partreg::testing {

/// Evaluates `cost` at `blocks` (one pointer per parameter block) with its Jacobians, and expects every entry
/// to match the central difference of the residuals with step 1e-6, to 1e-5 relative to 1 + the entry.
/// `context` names the evaluation point in failure messages.
inline void expect_jacobian_matches_central_differences(const ceres::CostFunction& cost,
                                                        std::vector<double*> blocks,
                                                        const std::string& context = "") {
  const std::vector<int>& sizes = cost.parameter_block_sizes();
  ASSERT_EQ(sizes.size(), blocks.size());
  const int residuals = cost.num_residuals();
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> pointers;
  for (int size : sizes) {
    jacobians.emplace_back(static_cast<std::size_t>(residuals * size));
    pointers.push_back(jacobians.back().data());
  }
  Eigen::VectorXd r(residuals);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), pointers.data()));
  const double h = 1e-6;
  for (std::size_t b = 0; b < sizes.size(); ++b)
    for (int c = 0; c < sizes[b]; ++c) {
      Eigen::VectorXd plus(residuals), minus(residuals);
      const double kept = blocks[b][c];
      blocks[b][c] = kept + h;
      cost.Evaluate(blocks.data(), plus.data(), nullptr);
      blocks[b][c] = kept - h;
      cost.Evaluate(blocks.data(), minus.data(), nullptr);
      blocks[b][c] = kept;
      const Eigen::VectorXd numeric = (plus - minus) / (2.0 * h);
      for (int i = 0; i < residuals; ++i)
        EXPECT_NEAR(jacobians[b][static_cast<std::size_t>(i * sizes[b] + c)], numeric[i],
                    1e-5 * (1.0 + std::abs(numeric[i])))
            << context << " block " << b << " column " << c << " residual " << i;
    }
}

}  // namespace partreg::testing
