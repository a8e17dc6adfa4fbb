#pragma once
/// \file
/// The slow commands a panel can start, run on worker threads so the window keeps drawing: a registration
/// and a training. Each collects its result into the state when it is ready. Scripts never come here: they
/// run every command synchronously, so replays are deterministic. Needs no window (tested without one).

#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"
#include "partreg/ui/executor.hpp"

namespace partreg::app {

/// A job's progress as its worker thread reports it and the UI thread reads it.
struct SharedProgress {
  std::mutex mutex;
  ui::JobProgress progress;
  /// A listener that stores each report here (to be called on the worker).
  static core::ProgressListener listener(const std::shared_ptr<SharedProgress>& shared);
};

/// A `register` command on its own thread; its result enters the state when it is ready.
class BackgroundRegistration {
 public:
  /// Starts the registration, or reports in the status line why it cannot (one already runs, bad options).
  void start(ui::AppState& state, const ui::Command& command);
  /// While it runs: the spaces fitted so far in state.registering and its elapsed time in the status line
  /// (the time of each fit is not known ahead: the solver stops when the cost settles). When it has ended:
  /// applies its result (unless another model was loaded meanwhile) or reports its failure. Call once a
  /// frame.
  void collect(ui::AppState& state);
  /// True from start() until collect() has taken the result (the window keeps drawing meanwhile).
  bool running() const { return running_.valid(); }

 private:
  std::optional<ui::RegistrationJob> job_;
  std::shared_ptr<SharedProgress> shared_;
  std::future<core::RegistrationResult> running_;
  std::chrono::steady_clock::time_point started_;
};

/// A `train` command on its own thread, with its progress in state.training while it runs. When it ends the
/// model it wrote is loaded (as the synchronous `train` does). Destroying it cancels a running training at
/// its next step and waits for it; nothing is then written.
class BackgroundTraining {
 public:
  BackgroundTraining() = default;
  BackgroundTraining(const BackgroundTraining&) = delete;
  BackgroundTraining& operator=(const BackgroundTraining&) = delete;
  ~BackgroundTraining();

  /// Starts training, or reports in the status line why it cannot (one already runs, no dataset folder).
  void start(ui::AppState& state, const ui::Command& command);
  /// Copies the progress into state.training; when training has ended, loads its model or reports its
  /// failure. Call once a frame.
  void collect(ui::AppState& state);
  /// True from start() until collect() has taken the result.
  bool running() const { return running_.valid(); }

 private:
  // Written by the worker, read by the UI thread.
  struct Shared {
    std::mutex mutex;
    ui::JobProgress progress;
    std::atomic<bool> cancel{false};
  };
  std::shared_ptr<Shared> shared_;
  std::optional<ui::TrainingJob> job_;
  std::future<std::string> running_;
};

}  // namespace partreg::app
