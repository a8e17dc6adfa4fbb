#include "partreg/commands/console.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <streambuf>

namespace partreg::app {
namespace {

// A stream buffer that accepts and drops everything.
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize count) override { return count; }
};

// The command line's choice, for the one command a process runs. State of the executable, not of the
// libraries: commands reach it through verbosity() and detail_log().
struct Console {
  Verbosity verbosity = Verbosity::normal;
  NullBuffer null_buffer;
  std::ostream null_stream{&null_buffer};
  std::streambuf* saved_error_buffer = nullptr;  // stderr's own buffer while --quiet holds it
  int saved_error_fd = -1;                       // descriptor 2 while --quiet points it at /dev/null
  // Static objects end before the streams' last flush at exit: stderr must not point here by then.
  ~Console() {
    if (saved_error_buffer) std::cerr.rdbuf(saved_error_buffer);
  }
};

Console& console() {
  static Console instance;
  return instance;
}

void set_quiet() {
  Console& state = console();
  state.verbosity = Verbosity::quiet;
  if (!state.saved_error_buffer) state.saved_error_buffer = std::cerr.rdbuf(&state.null_buffer);
  // Libraries write to descriptor 2 themselves (Ceres's residual warnings, VTK, Embree): quiet is quiet for
  // them too. The descriptor is kept for the error line.
  if (state.saved_error_fd >= 0) return;
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null < 0) return;
  state.saved_error_fd = ::fcntl(2, F_DUPFD_CLOEXEC, 3);
  if (state.saved_error_fd >= 0) ::dup2(null, 2);
  ::close(null);
}

}  // namespace

void add_verbosity_flags(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands({})) {
    add_verbosity_flags(*command);  // nested ones too: `figure compare ... --quiet`
    CLI::Option* quiet = command->add_flag_callback("-q,--quiet", set_quiet,
                                                    "print nothing on stderr but an error's one line");
    command
        ->add_flag_callback(
            "-v,--verbose", [] { console().verbosity = Verbosity::verbose; },
            "also print detail lines (every progress step, per-fit figures)")
        ->excludes(quiet);
  }
}

Verbosity verbosity() { return console().verbosity; }

std::ostream& detail_log() {
  return console().verbosity == Verbosity::verbose ? std::cerr : console().null_stream;
}

void restore_error_stream() {
  Console& state = console();
  if (state.saved_error_buffer) std::cerr.rdbuf(state.saved_error_buffer);
  state.saved_error_buffer = nullptr;
  if (state.saved_error_fd >= 0) {
    std::cerr.flush();
    ::dup2(state.saved_error_fd, 2);
    ::close(state.saved_error_fd);
    state.saved_error_fd = -1;
  }
}

std::string clock_text(double seconds) {
  const long s = std::lround(seconds);
  std::ostringstream out;
  out << s / 60 << ':' << std::setw(2) << std::setfill('0') << s % 60;
  return out.str();
}

ProgressDisplay::ProgressDisplay(ProgressStyle style) : style_(std::move(style)), terminal_(::isatty(2)) {}

ProgressDisplay::~ProgressDisplay() { finish(); }

void ProgressDisplay::finish() {
  if (bar_drawn_) std::cerr << '\n' << std::flush;
  bar_drawn_ = false;
}

void ProgressDisplay::print(const std::string& line) {
  std::cerr << (bar_drawn_ ? "\r\033[K" : "") << line << '\n' << std::flush;
  bar_drawn_ = false;
}

core::ProgressListener ProgressDisplay::listener() {
  return [this](const core::Progress& progress) { (*this)(progress); };
}

std::string ProgressDisplay::status(const core::Progress& progress) const {
  std::ostringstream out;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  out << progress.done << '/' << progress.total << ' ' << style_.unit << ", " << clock_text(elapsed)
      << " elapsed";
  if (progress.done > 0 && progress.total >= progress.done) {
    const double left = step_seconds_ / static_cast<double>(progress.done) *
                        static_cast<double>(progress.total - progress.done);
    out << (progress.bounded ? ", at most " : ", ~") << clock_text(left) << " left";
  }
  return out.str();
}

void ProgressDisplay::draw_bar(const core::Progress& progress) {
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(kWidth * std::min(1.0, progress.fraction()));
  std::cerr << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] "
            << status(progress) << "\033[K" << std::flush;
  bar_drawn_ = true;
  if (progress.done >= progress.total && !progress.bounded) finish();
}

void ProgressDisplay::operator()(const core::Progress& progress) {
  if (verbosity() == Verbosity::quiet) return;
  const Clock::time_point now = Clock::now();
  if (!progress.aside) step_seconds_ += std::chrono::duration<double>(now - last_).count();
  last_ = now;
  const bool verbose = verbosity() == Verbosity::verbose;
  const bool show_line = !progress.line.empty() && (verbose || !style_.lines_are_detail);
  const bool counted = progress.total > 0 && progress.done > 0;
  if (terminal_) {
    if (show_line) std::cerr << "\r\033[K" << progress.line << '\n';
    bar_drawn_ = bar_drawn_ && !show_line;
    if (progress.total > 0) draw_bar(progress);
    return;
  }
  const int percent = progress.total > 0 ? static_cast<int>(100 * progress.fraction()) : 0;
  const bool count_due =
      counted && (verbose || (style_.log_every_percent > 0 &&
                              (percent >= next_percent_ || progress.done == progress.total)));
  if (show_line)
    std::cerr << (counted ? "[" + status(progress) + "] " : "") << progress.line << '\n';
  else if (count_due)
    std::cerr << status(progress) << '\n';
  if (count_due) next_percent_ = percent + style_.log_every_percent;
}

}  // namespace partreg::app
