#pragma once
/// \file
/// Every file partreg writes goes through here: written under a temporary name in the destination's folder,
/// then renamed into place, so a failure or a crash never leaves a half-written output behind.

#include <filesystem>
#include <functional>

namespace partreg::io {

/// Calls writer(temporary) and renames the temporary onto `destination`. If the writer throws, the temporary
/// is removed and the exception propagates; the destination is untouched.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path& temporary)>& writer);

/// The lower-case extension of a path including the dot (".ply"), or "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

}  // namespace partreg::io
