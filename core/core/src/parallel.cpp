#include "partreg/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace partreg::core {

namespace {

// 0: no budget set on this thread (the default applies).
thread_local int budget_of_this_thread = 0;

}  // namespace

int default_thread_count() { return std::max(1u, std::thread::hardware_concurrency()); }

int thread_budget() { return budget_of_this_thread > 0 ? budget_of_this_thread : default_thread_count(); }

ThreadBudget::ThreadBudget(int threads) : previous_(budget_of_this_thread) {
  budget_of_this_thread = threads > 0 ? threads : default_thread_count();
}

ThreadBudget::~ThreadBudget() { budget_of_this_thread = previous_; }

void parallel_for(Eigen::Index count, const std::function<void(Eigen::Index, Eigen::Index)>& body,
                  int threads, Eigen::Index minimum_chunk) {
  if (count <= 0) return;
  const Eigen::Index wanted = threads > 0 ? std::min(threads, thread_budget()) : thread_budget();
  const Eigen::Index workers =
      std::max<Eigen::Index>(1, std::min(wanted, count / std::max<Eigen::Index>(1, minimum_chunk)));
  if (workers == 1) {
    body(0, count);
    return;
  }
  // Chunks are handed out as workers come free, not dealt in advance: the items of one loop can differ in
  // cost several times over (pose hypotheses that converge early, or see more points), and halves dealt in
  // advance left one thread idle for a third of the pose search (docs/benchmarks.md). About eight chunks
  // per worker.
  const Eigen::Index chunk = std::max<Eigen::Index>(1, count / (8 * workers));
  std::atomic<Eigen::Index> next{0};
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  const auto work = [&](Eigen::Index w) {
    try {
      const ThreadBudget one(1);  // this thread is part of the caller's budget: nested loops stay serial
      for (Eigen::Index begin = next.fetch_add(chunk); begin < count; begin = next.fetch_add(chunk))
        body(begin, std::min(count, begin + chunk));
    } catch (...) {
      errors[static_cast<std::size_t>(w)] = std::current_exception();
      next = count;  // the others stop at their next chunk
    }
  };
  std::vector<std::thread> pool;
  for (Eigen::Index w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);  // the calling thread is one of the workers
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace partreg::core
