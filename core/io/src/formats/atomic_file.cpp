#include "partreg/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "partreg/core/errors.hpp"

namespace partreg::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingTag = ".partial-";

// The hidden sibling a destination is staged under: ".NAME.partial-PID-N".
std::string staging_prefix(const fs::path& destination) {
  return "." + destination.filename().string() + kStagingTag;
}

bool process_is_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH); }

// Staging files and folders of `destination` left by runs that were killed: their process is gone.
void remove_stale_staging(const fs::path& destination) {
  const fs::path folder = destination.parent_path().empty() ? "." : destination.parent_path();
  const std::string prefix = staging_prefix(destination);
  std::error_code error;
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    std::error_code ignored;
    if (!process_is_alive(pid)) fs::remove_all(entry->path(), ignored);
  }
}

// Opening a FIFO for writing blocks until a process opens it for reading, and a run would hang after all
// its work. A non-blocking open fails (ENXIO) while nobody reads: retry for a while, then give up. The
// descriptor returned (or -1 for anything but a FIFO) is held while the writer opens the FIFO again, so
// that open finds the reader.
int wait_for_fifo_reader(const fs::path& path, const fs::path& destination) {
  std::error_code error;
  if (!fs::is_fifo(fs::status(path, error))) return -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kFifoReaderWaitSeconds);
  for (;;) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd >= 0) return fd;
    if (errno != ENXIO)
      throw InputError("cannot write " + destination.string() + ": " + std::strerror(errno));
    if (std::chrono::steady_clock::now() > deadline)
      throw InputError("cannot write " + destination.string() + ": no process read the FIFO within " +
                       std::to_string(kFifoReaderWaitSeconds) + " s");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace

OutputTarget resolve_output(const fs::path& destination) {
  if (destination == "-") return {"/dev/stdout", true};
  std::error_code error;
  fs::path target = destination;
  // A symbolic link is followed to the file it names (which may not exist yet), so the link stays.
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, error)); ++hops) {
    if (hops == 40) throw InputError("cannot write " + destination.string() + ": too many symbolic links");
    const fs::path link = fs::read_symlink(target, error);
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const fs::file_status status = fs::status(target, error);
  if (fs::is_directory(status)) throw InputError("cannot write " + destination.string() + ": it is a folder");
  if (fs::exists(status) && !fs::is_regular_file(status)) return {target, true};  // device, FIFO, socket
  const fs::path folder = target.parent_path().empty() ? "." : target.parent_path();
  if (!fs::is_directory(folder, error))
    throw InputError("cannot write " + destination.string() + ": folder " + folder.string() + " does not exist");
  return {target, false};
}

void write_atomically(const fs::path& destination, const std::function<void(const fs::path& temporary)>& writer) {
  static std::atomic<int> counter{0};
  const OutputTarget target = resolve_output(destination);
  try {
    if (target.direct) {
      const int reader_held = wait_for_fifo_reader(target.path, destination);
      try {
        writer(target.path);
      } catch (...) {
        if (reader_held >= 0) ::close(reader_held);
        throw;
      }
      if (reader_held >= 0) ::close(reader_held);
      return;
    }
    remove_stale_staging(target.path);
    const fs::path folder = target.path.parent_path().empty() ? "." : target.path.parent_path();
    const fs::path temporary = folder / (staging_prefix(target.path) + std::to_string(::getpid()) + "-" +
                                         std::to_string(counter++));
    try {
      writer(temporary);
      fs::rename(temporary, target.path);
    } catch (...) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw;
    }
  } catch (const fs::filesystem_error& e) {
    // The message names the destination, never the hidden staging file.
    throw InputError("cannot write " + destination.string() + ": " + e.code().message());
  }
}

StagedFolder::StagedFolder(const fs::path& destination) : destination_(destination) {
  if (fs::exists(destination) && !(fs::is_directory(destination) && fs::is_empty(destination)))
    throw UsageError("output folder " + destination.string() + " exists and is not empty");
  const fs::path parent = destination.has_parent_path() ? destination.parent_path() : fs::path(".");
  std::error_code error;
  fs::create_directories(parent, error);
  if (error) throw InputError("cannot create " + parent.string() + ": " + error.message());
  remove_stale_staging(destination);
  staging_ = parent / (staging_prefix(destination) + std::to_string(::getpid()));
  fs::remove_all(staging_, error);
  fs::create_directories(staging_, error);
  if (error) throw InputError("cannot create output folder " + destination.string() + ": " + error.message());
}

StagedFolder::~StagedFolder() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
  }
}

void StagedFolder::commit() {
  std::error_code error;
  if (fs::exists(destination_)) fs::remove(destination_, error);  // empty, checked above
  fs::rename(staging_, destination_, error);
  if (error) throw InputError("cannot write output folder " + destination_.string() + ": " + error.message());
  committed_ = true;
}

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace partreg::io
