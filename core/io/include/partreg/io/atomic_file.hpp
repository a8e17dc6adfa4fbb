#pragma once
/// \file
/// Every file partreg writes goes through here. A regular file or a new path is written under a hidden
/// temporary name in its folder (".NAME.partial-PID-N") and renamed into place, so a failure or a crash never
/// leaves a half-written output behind; temporaries of killed runs are removed on the next write to the same
/// place. A device, a FIFO or "-" (stdout) is written directly: renaming over /dev/null would replace the
/// device. A symbolic link is followed to the file it names. A FIFO is written once a process reads it: after
/// kFifoReaderWaitSeconds without one, the write fails with an InputError instead of blocking forever.

#include <filesystem>
#include <functional>
#include <string>

namespace partreg::io {

/// Where the bytes for a destination go.
struct OutputTarget {
  std::filesystem::path path;  ///< the file to write: symbolic links followed, "-" as /dev/stdout
  bool direct = false;         ///< true for a device, FIFO or stdout: written in place, never renamed over
};

/// How long a write to a FIFO waits for a process that reads it (seconds).
inline constexpr int kFifoReaderWaitSeconds = 10;

/// Resolves `destination` as write_atomically does. InputError naming it for a folder, a missing parent
/// folder or a loop of symbolic links; so commands call it on every output before they start.
OutputTarget resolve_output(const std::filesystem::path& destination);

/// Calls writer(temporary) and renames the temporary onto `destination` (or calls writer(destination) for a
/// direct target). If the writer throws, the temporary is removed and the exception propagates; the
/// destination is untouched. File-system errors become an InputError naming `destination`.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path& temporary)>& writer);

/// An output folder written in full or not at all: files go to a hidden sibling folder that commit() renames
/// to the destination; without commit() (a failure) the sibling is removed. The destination must not exist
/// or be empty (UsageError otherwise), so nothing of somebody else's is ever overwritten.
class StagedFolder {
 public:
  explicit StagedFolder(const std::filesystem::path& destination);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  /// Where to write the files now.
  const std::filesystem::path& staging() const { return staging_; }
  void commit();

 private:
  std::filesystem::path destination_, staging_;
  bool committed_ = false;
};

/// The lower-case extension of a path including the dot (".ply"), or "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

}  // namespace partreg::io
