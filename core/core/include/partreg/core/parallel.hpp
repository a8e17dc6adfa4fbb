#pragma once
/// \file
/// A minimal parallel loop on std::thread: the core stays free of threading libraries, and the loops
/// it parallelises (E-steps, nearest-neighbour batches, kernel products) are simple ranges.

#include <Eigen/Core>
#include <functional>

namespace partreg::core {

/// Threads used by parallel_for when `threads` is 0: the hardware concurrency (at least 1).
int default_thread_count();

/// Calls body(begin, end) on contiguous chunks covering [0, count), on up to `threads` threads
/// (0 = default_thread_count()). Small ranges run on the calling thread. Exceptions propagate.
void parallel_for(Eigen::Index count, const std::function<void(Eigen::Index, Eigen::Index)>& body,
                  int threads = 0, Eigen::Index minimum_chunk = 64);

}  // namespace partreg::core
