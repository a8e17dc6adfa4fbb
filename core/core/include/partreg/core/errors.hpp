#pragma once
/// \file
/// The two kinds of failure partreg reports. Libraries throw; only app/ turns them into exit codes.

#include <stdexcept>

namespace partreg {

/// Bad data or a failing resource at run time (missing file, NaN cloud, corrupt model). Exit code 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A request that can never succeed as stated (negative beta, unknown mode). Exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace partreg
