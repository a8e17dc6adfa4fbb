#pragma once
/// \file
/// Runs the real `partreg` executable (PARTREG_EXECUTABLE, set by the test's CMake) as a user would.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace partreg::testing {

struct Outcome {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// `partreg ARGUMENTS`, through the shell.
inline Outcome run_partreg(const std::string& arguments) {
  const std::string command = std::string(PARTREG_EXECUTABLE) + " " + arguments + " 2>&1";
  Outcome result;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace partreg::testing
