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

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace partreg::io
