// The parallel loop and the thread budget (core/parallel.hpp).
#include "partreg/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace partreg::core {
namespace {

TEST(ParallelFor, VisitsEveryItemOnceWithinTheBudget) {
  for (const int budget : {1, 2, 3, 8})
    for (const Eigen::Index count : {1, 2, 7, 64, 1000}) {
      const ThreadBudget limit(budget);
      std::vector<std::atomic<int>> visits(static_cast<std::size_t>(count));
      std::mutex mutex;
      std::set<std::thread::id> threads;
      std::atomic<int> nested_budget_above_one{0};
      parallel_for(
          count,
          [&](Eigen::Index begin, Eigen::Index end) {
            ASSERT_LE(0, begin);
            ASSERT_LT(begin, end);
            ASSERT_LE(end, count);
            for (Eigen::Index i = begin; i < end; ++i) ++visits[static_cast<std::size_t>(i)];
            if (thread_budget() > 1) ++nested_budget_above_one;
            const std::lock_guard<std::mutex> lock(mutex);
            threads.insert(std::this_thread::get_id());
          },
          0, 1);
      for (const std::atomic<int>& v : visits)
        EXPECT_EQ(v.load(), 1) << budget << " threads, " << count << " items";
      EXPECT_LE(threads.size(), static_cast<std::size_t>(budget));
      // A body that runs on several threads sees a budget of one: loops nested in it stay serial.
      if (threads.size() > 1) EXPECT_EQ(nested_budget_above_one.load(), 0);
      EXPECT_EQ(thread_budget(), budget);  // the caller's budget is back after the loop
    }
}

// The loop's items differ in cost (pose hypotheses): a thread that is free takes the next chunk. Item 0
// waits for items 10 .. 99 (with two threads a chunk is about a sixteenth of the items). Dealt in halves in
// advance, item 0's thread would also own items 10 .. 49, and item 0 would wait forever; here it waits at
// most 20 s, then reports the items still undone.
TEST(ParallelFor, AFreeThreadTakesTheNextChunk) {
  constexpr Eigen::Index kCount = 100, kWaitedFor = 90;
  const ThreadBudget two(2);
  std::atomic<Eigen::Index> done{0};  // of the items waited for
  Eigen::Index undone_when_item_0_gave_up = -1;
  parallel_for(
      kCount,
      [&](Eigen::Index begin, Eigen::Index end) {
        for (Eigen::Index i = begin; i < end; ++i) {
          if (i == 0) {
            const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(20);
            while (done.load() < kWaitedFor && std::chrono::steady_clock::now() < limit)
              std::this_thread::sleep_for(std::chrono::milliseconds(1));
            undone_when_item_0_gave_up = kWaitedFor - done.load();
          }
          if (i >= kCount - kWaitedFor) ++done;
        }
      },
      0, 1);
  EXPECT_EQ(undone_when_item_0_gave_up, 0);
  EXPECT_EQ(done.load(), kWaitedFor);
}

TEST(ParallelFor, AnExceptionInOneChunkReachesTheCaller) {
  const ThreadBudget four(4);
  std::atomic<int> calls{0};
  EXPECT_THROW(parallel_for(
                   1000,
                   [&](Eigen::Index begin, Eigen::Index end) {
                     ++calls;
                     if (begin <= 500 && 500 < end) throw std::runtime_error("item 500");
                   },
                   0, 1),
               std::runtime_error);
  EXPECT_GT(calls.load(), 0);
}

}  // namespace
}  // namespace partreg::core
