#include "partreg/core/parallel.hpp"

#include <algorithm>
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
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  const Eigen::Index chunk = (count + workers - 1) / workers;
  for (Eigen::Index w = 0; w < workers; ++w) {
    const Eigen::Index begin = w * chunk, end = std::min(count, begin + chunk);
    pool.emplace_back([&, w, begin, end] {
      try {
        const ThreadBudget one(1);  // this thread is part of the caller's budget: nested loops stay serial
        if (begin < end) body(begin, end);
      } catch (...) {
        errors[static_cast<std::size_t>(w)] = std::current_exception();
      }
    });
  }
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace partreg::core
