// CPD gives the same bits whatever the thread count and whatever the process allocated before (so
// the evaluation's shards equal the unsharded run, and the Python module the command line).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/synthetic/synthetic.hpp"

namespace partreg::core {
namespace {

struct Pair {
  Points source, target;
};

Pair mug_pair(int points) {
  const auto mugs = make_synthetic_category(SyntheticCategory::mug, 2, 11);
  return {sample_correspondences(SyntheticCategory::mug, mugs[0].shape_parameters, points, 1).points,
          sample_correspondences(SyntheticCategory::mug, mugs[1].shape_parameters, points, 2).points};
}

Points nonrigid(const Pair& pair, int threads) {
  const ThreadBudget budget(threads);
  NonrigidCpdSettings settings;
  settings.solver = NonrigidCpdSettings::Solver::fast;  // the fast E-step: blocks, cells, float arrays
  return register_nonrigid(pair.source, pair.target, settings).moved;
}

TEST(CpdRepeatability, TheSameBitsAtAnyThreadCount) {
  const Pair pair = mug_pair(1500);
  const Points one = nonrigid(pair, 1);
  for (int threads : {2, 3, 5}) EXPECT_EQ(nonrigid(pair, threads), one) << threads << " threads";
  RigidCpdSettings rigid;
  const ThreadBudget budget(1);
  const Eigen::Matrix4d T = register_rigid(pair.source, pair.target, rigid).T_target_source();
  rigid.threads = 3;
  const ThreadBudget three(3);
  EXPECT_EQ(register_rigid(pair.source, pair.target, rigid).T_target_source(), T);
}

TEST(CpdRepeatability, TheSameBitsWhereverTheHeapPutsItsBuffers) {
  const Pair pair = mug_pair(1500);
  const Points first = nonrigid(pair, 1);
  // Allocations of odd sizes kept alive shift where the E-step's buffers land (to any 16-byte offset).
  std::vector<std::unique_ptr<char[]>> held;
  for (int shift = 1; shift <= 6; ++shift) {
    for (int i = 0; i < 40; ++i)
      held.emplace_back(new char[static_cast<std::size_t>(16 * shift + 8 * i + 1)]);
    EXPECT_EQ(nonrigid(pair, 1), first) << "after allocation round " << shift;
  }
}

}  // namespace
}  // namespace partreg::core
