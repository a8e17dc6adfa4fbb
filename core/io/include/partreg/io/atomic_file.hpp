#pragma once
/// \file
/// Every file partreg writes goes through here: written under a temporary name in the destination's folder,
/// then renamed into place, so a failure or a crash never leaves a half-written output behind.

#include <filesystem>
#include <functional>
#include <string>

namespace partreg::io {

/// Calls writer(temporary) and renames the temporary onto `destination`. If the writer throws, the temporary
/// is removed and the exception propagates; the destination is untouched.
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
