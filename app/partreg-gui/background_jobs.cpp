#include "background_jobs.hpp"

#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>

namespace partreg::app {
namespace {

void report(ui::AppState& state, const std::string& text, bool error) {
  state.status = text;
  state.status_is_error = error;
}

bool finished(const std::future<std::string>& future) {
  return future.valid() && future.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

// The job for a command, or nothing with the reason in the status line (bad options, nothing loaded).
template <typename Prepare>
auto prepared(ui::AppState& state, Prepare prepare) -> std::optional<decltype(prepare())> {
  try {
    return prepare();
  } catch (const std::exception& e) {
    report(state, e.what(), true);
    return std::nullopt;
  }
}

// Thrown from the progress callback to stop a training nobody waits for any more.
struct Cancelled : std::exception {
  const char* what() const noexcept override { return "training cancelled"; }
};

}  // namespace

core::ProgressListener SharedProgress::listener(const std::shared_ptr<SharedProgress>& shared) {
  return [shared](const core::Progress& step) {
    const std::lock_guard<std::mutex> lock(shared->mutex);
    shared->progress.fraction = step.fraction();
    shared->progress.line = step.line;
  };
}

void BackgroundRegistration::start(ui::AppState& state, const ui::Command& command) {
  if (running_.valid()) {
    report(state, "a registration is already running", true);
    return;
  }
  job_ = prepared(state, [&] { return ui::prepare_registration(state, command); });
  if (!job_) return;
  shared_ = std::make_shared<SharedProgress>();
  shared_->progress = {true, 0.0, "registering (" + core::enum_name(job_->settings.variant) + ")"};
  state.registering = shared_->progress;
  running_ = std::async(std::launch::async, [job = *job_, listener = SharedProgress::listener(shared_)] {
    return job.run(listener);
  });
  started_ = std::chrono::steady_clock::now();
  report(state, "registering (" + core::enum_name(job_->settings.variant) + ")...", false);
}

void BackgroundRegistration::collect(ui::AppState& state) {
  if (!running_.valid()) return;
  {
    const std::lock_guard<std::mutex> lock(shared_->mutex);
    state.registering = shared_->progress;
  }
  if (running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    char text[96];
    std::snprintf(text, sizeof text, "registering (%s)... %.1f s",
                  core::enum_name(job_->settings.variant).c_str(), seconds);
    report(state, text, false);
    return;
  }
  state.registering = ui::JobProgress{};
  try {
    core::RegistrationResult result = running_.get();
    if (state.shapes.model != job_->model) {  // another model was loaded meanwhile: the result is stale
      report(state, "registration finished for a model no longer loaded: discarded", true);
      return;
    }
    report(state, ui::apply_registration(state, *job_, std::move(result)).message, false);
  } catch (const std::exception& e) {
    report(state, std::string("registration failed: ") + e.what(), true);
  }
}

BackgroundTraining::~BackgroundTraining() {
  if (shared_) shared_->cancel = true;
  // The future's destructor waits for the worker, which stops at its next step.
}

void BackgroundTraining::start(ui::AppState& state, const ui::Command& command) {
  if (running_.valid()) {
    const int percent = static_cast<int>(100.0 * state.training.fraction);
    report(state, "a training is already running (" + std::to_string(percent) + "% done): wait for it", true);
    return;
  }
  job_ = prepared(state, [&] { return ui::prepare_training(state, command); });
  if (!job_) return;
  shared_ = std::make_shared<Shared>();
  shared_->progress = {true, 0.0, "starting"};
  state.training = shared_->progress;
  // The worker holds its own copies: the job and the shared progress outlive this object if need be.
  running_ = std::async(std::launch::async, [job = *job_, shared = shared_] {
    return job.run([&shared](const core::TrainingProgress& step) {
      if (shared->cancel) throw Cancelled();
      const std::lock_guard<std::mutex> lock(shared->mutex);
      shared->progress.fraction = step.fraction();
      shared->progress.line = step.line;
    });
  });
  report(state, "training on " + job_->dataset_path + "...", false);
}

void BackgroundTraining::collect(ui::AppState& state) {
  if (!running_.valid()) return;
  {
    const std::lock_guard<std::mutex> lock(shared_->mutex);
    state.training = shared_->progress;
  }
  if (!finished(running_)) return;
  state.training = ui::JobProgress{};
  try {
    const std::string summary = running_.get();
    report(state, ui::apply_training(state, *job_, summary).message, false);
  } catch (const std::exception& e) {
    report(state, std::string("training failed: ") + e.what(), true);
  }
}

}  // namespace partreg::app
