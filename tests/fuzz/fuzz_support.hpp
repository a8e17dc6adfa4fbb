#pragma once
/// \file
/// What every libFuzzer harness shares: the input as a file with a given extension (partreg's readers take
/// paths and choose the format by extension), and the rule that a reader may refuse an input only with
/// partreg's own InputError or UsageError. Anything else escaping (a library's exception, a crash, a
/// sanitizer report, a hang) is a finding.

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "partreg/core/errors.hpp"

namespace partreg::fuzz {

/// A folder of this process's own under the temporary directory, made once.
inline const std::filesystem::path& scratch_folder() {
  static const std::filesystem::path folder = [] {
    const auto path = std::filesystem::temp_directory_path() / ("partreg-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return folder;
}

/// Writes the input to `name` (e.g. "input.ply") in the scratch folder and calls `read` on that path.
inline void read_as_file(const std::uint8_t* data, std::size_t size, const std::string& name,
                         const std::function<void(const std::filesystem::path&)>& read) {
  const std::filesystem::path path = scratch_folder() / name;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read(path);
  } catch (const InputError&) {
  } catch (const UsageError&) {
  }
}

}  // namespace partreg::fuzz
