#pragma once
/// \file
/// Locating ../shared/data for tests and benchmarks. Real data is never copied into the repository:
/// tests that need it skip with a clear message when it is absent.

#include <cstdlib>
#include <filesystem>
#include <string>

namespace partreg::testing {

/// The shared data folder: $PARTREG_DATA if set, else the path CMake was configured with.
inline std::filesystem::path shared_data_dir() {
  if (const char* from_env = std::getenv("PARTREG_DATA")) return from_env;
  return PARTREG_DATA_DIR;
}

/// Full path of `relative` inside the shared data folder (it may not exist).
inline std::filesystem::path shared_data(const std::string& relative) { return shared_data_dir() / relative; }

}  // namespace partreg::testing

/// Skips the current test, saying what is missing, when a shared data file or folder is absent.
#define PARTREG_REQUIRE_SHARED_DATA(path)                                                          \
  do {                                                                                             \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << (path).string(); \
  } while (0)
