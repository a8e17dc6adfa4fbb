#pragma once
/// \file
/// A minimal parallel loop on std::thread, and the one thread budget every parallel part of partreg honours.
/// The core stays free of threading libraries, and the loops it parallelises (E-steps, nearest-neighbour
/// batches, kernel products, the parts of a registration) are simple ranges.
///
/// The budget: a front end's `--threads N` (or the Python module's `threads=`) holds a ThreadBudget on the
/// thread that does the work; every parallel_for started from that thread uses at most N threads in all,
/// the calling thread included. The threads a parallel_for starts run their chunks with a budget of one, so
/// nested loops (a KD-tree batch inside a registration's part) never multiply the count. The evaluation's
/// TBB arena is sized by the same N and gives each of its tasks a budget of one.

#include <Eigen/Core>
#include <functional>

namespace partreg::core {

/// Threads used when nothing limits them: the hardware concurrency (at least 1).
int default_thread_count();

/// The calling thread's budget: what its parallel_for calls may use (default_thread_count() unless a
/// ThreadBudget says otherwise).
int thread_budget();

/// Limits the calling thread's parallel work to `threads` threads while it lives (0 =
/// default_thread_count()). Budgets nest: the inner one applies until it ends, then the outer one again.
class ThreadBudget {
 public:
  explicit ThreadBudget(int threads);
  ~ThreadBudget();
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

 private:
  int previous_;
};

/// Calls body(begin, end) on contiguous chunks covering [0, count), on up to min(`threads`, thread_budget())
/// threads (`threads` 0 = the budget), the calling thread one of them; each thread takes the next chunk when
/// it is free, so a chunk's thread and the order chunks run in vary from run to run (a body must write only
/// its own items' results). Small ranges run on the calling thread. Exceptions propagate (one of them, when
/// several threads throw; the others stop at their next chunk).
void parallel_for(Eigen::Index count, const std::function<void(Eigen::Index, Eigen::Index)>& body,
                  int threads = 0, Eigen::Index minimum_chunk = 64);

}  // namespace partreg::core
