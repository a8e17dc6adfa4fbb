#include "partreg/io/atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>

#include "partreg/core/errors.hpp"

namespace partreg::io {

void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path& temporary)>& writer) {
  static std::atomic<int> counter{0};
  const std::filesystem::path folder = destination.parent_path().empty() ? "." : destination.parent_path();
  if (!std::filesystem::is_directory(folder))
    throw InputError("cannot write " + destination.string() + ": folder " + folder.string() +
                     " does not exist");
  const std::filesystem::path temporary =
      folder / ("." + destination.filename().string() + ".partial-" + std::to_string(::getpid()) + "-" +
                std::to_string(counter++));
  try {
    writer(temporary);
    std::filesystem::rename(temporary, destination);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

StagedFolder::StagedFolder(const std::filesystem::path& destination) : destination_(destination) {
  namespace fs = std::filesystem;
  if (fs::exists(destination) && !(fs::is_directory(destination) && fs::is_empty(destination)))
    throw UsageError("output folder " + destination.string() + " exists and is not empty");
  const fs::path parent = destination.has_parent_path() ? destination.parent_path() : fs::path(".");
  fs::create_directories(parent);
  staging_ = parent / ("." + destination.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(staging_);
  fs::create_directories(staging_);
}

StagedFolder::~StagedFolder() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(staging_, ignored);
  }
}

void StagedFolder::commit() {
  if (std::filesystem::exists(destination_)) std::filesystem::remove(destination_);  // empty, checked above
  std::filesystem::rename(staging_, destination_);
  committed_ = true;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace partreg::io
