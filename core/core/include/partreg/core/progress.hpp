#pragma once
/// \file
/// How a long computation (training, CPD, evaluation) tells its caller how far it is. The library only calls
/// a ProgressListener; front ends decide what to draw: the command line a bar with the time left on a
/// terminal or plain lines in a log (app/partreg/commands/console.hpp), the window a progress bar
/// (ui::JobProgress).

#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace partreg::core {

/// One report: `done` of `total` steps of the same kind finished, and what the last one did.
struct Progress {
  std::size_t done = 0;   ///< steps finished
  std::size_t total = 0;  ///< steps planned; 0 while unknown. A bound, not a promise, where `bounded` is set
  std::string line;       ///< a line worth logging about the last step; empty for a plain count
  /// The total is only an upper bound (CPD's iteration cap): the computation may end before it.
  bool bounded = false;
  /// Time since the previous report went into work that is not one of these steps (eval training a fold):
  /// a time-left estimate should not count it towards the time per step.
  bool aside = false;
  /// done / total in [0, 1] (0 while total is 0).
  double fraction() const { return total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 0.0; }
};

/// Called after each step. The library calls it on one thread at a time (callers of parallel work
/// serialise their reports), not always the thread that started the computation. An exception thrown from
/// it ends the computation and propagates (the window stops a training nobody waits for this way).
using ProgressListener = std::function<void(const Progress&)>;

/// Counts the steps of a computation with a known number of them and reports each to a listener (if any).
/// step() may be called from several threads: reports go out one at a time, counted in the order they do.
class ProgressCounter {
 public:
  /// `listener` must outlive the counter.
  ProgressCounter(std::size_t total, const ProgressListener& listener) : total_(total), listener_(listener) {}
  /// Whether anyone listens (so that callers build lines only when they are read).
  bool wanted() const { return static_cast<bool>(listener_); }
  /// One more step done; `line` says what it did.
  void step(const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    if (listener_) listener_(Progress{done_, total_, line});
  }

 private:
  std::mutex mutex_;
  std::size_t done_ = 0;
  const std::size_t total_;
  const ProgressListener& listener_;
};

}  // namespace partreg::core
