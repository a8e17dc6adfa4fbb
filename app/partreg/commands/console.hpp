#pragma once
/// \file
/// What a command writes on stderr: how much (--quiet, --verbose, declared once for every subcommand) and
/// how progress looks (a bar with the time left on a terminal, plain lines in a log). Logs and progress go to
/// stderr; results to stdout or files (DESIGN.md).

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

#include "partreg/core/progress.hpp"

namespace partreg::app {

/// quiet: nothing on stderr but an error's one line; normal: what the command did and its progress;
/// verbose: also the detail lines (every progress report, per-fit figures).
enum class Verbosity { quiet, normal, verbose };

/// Adds -q/--quiet and -v/--verbose to every subcommand of `app`, nested ones included; call once, after
/// adding the subcommands.
/// --quiet silences stderr from the moment it is parsed until restore_error_stream().
void add_verbosity_flags(CLI::App& app);

/// What the command line chose (normal until a flag is parsed).
Verbosity verbosity();

/// stderr with --verbose, a stream that drops everything otherwise.
std::ostream& detail_log();

/// Gives stderr its own buffer back, so main.cpp's error line shows even with --quiet.
void restore_error_stream();

/// How a ProgressDisplay treats the reports of one computation.
struct ProgressStyle {
  std::string unit = "steps";  ///< what is counted, plural ("CPDs", "rows", "iterations")
  /// Reports' lines are detail (CPD's per-iteration lines): shown only with --verbose. Otherwise each is
  /// logged as it comes, above the bar on a terminal.
  bool lines_are_detail = false;
  /// In a log (stderr not a terminal), a bare count is printed every this many percent; 0 = never (then
  /// only the reports with a line are).
  int log_every_percent = 0;
};

/// Draws core::Progress reports on stderr: on a terminal a bar "[####....] 3/12 CPDs, 0:04 elapsed, ~0:11
/// left" redrawn in place, with lines above it; in a log one line per report that has one, prefixed with the
/// count and the time left. The time left counts only time spent on the steps themselves (not the time a
/// report marks `aside`, such as eval's training). Nothing with --quiet.
class ProgressDisplay {
 public:
  explicit ProgressDisplay(ProgressStyle style);
  ~ProgressDisplay();  ///< finish()
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  void operator()(const core::Progress& progress);
  /// A listener for the library that reports here (the display must outlive the computation).
  core::ProgressListener listener();
  /// Ends a bar still on its line with a newline, so that later lines start on their own.
  void finish();
  /// Writes `line` on stderr above the bar (a warning, a note between steps); the next report redraws the bar.
  void print(const std::string& line);

 private:
  using Clock = std::chrono::steady_clock;
  std::string status(const core::Progress& progress) const;
  void draw_bar(const core::Progress& progress);

  ProgressStyle style_;
  bool terminal_ = false, bar_drawn_ = false;
  Clock::time_point start_ = Clock::now(), last_ = start_;
  double step_seconds_ = 0.0;  // time spent on counted steps (reports not `aside`)
  int next_percent_ = 0;
};

/// "m:ss" for a duration in seconds (the elapsed and left times of progress lines).
std::string clock_text(double seconds);

}  // namespace partreg::app
