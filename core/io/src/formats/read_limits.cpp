#include "partreg/io/read_limits.hpp"

#include <algorithm>

#include "partreg/core/errors.hpp"

namespace partreg::io {

std::uint64_t checked_input_size(const std::filesystem::path& path) {
  return checked_input_size(path, kReadBudget.max_bytes);
}

std::uint64_t checked_input_size(const std::filesystem::path& path, std::uint64_t max_bytes) {
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    if (std::filesystem::exists(path, error)) throw InputError(name + " is not a regular file");
    throw InputError("no such file: " + name);
  }
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) throw InputError("cannot read " + name + ": " + error.message());
  if (size == 0) throw InputError(name + " is empty");
  if (size > max_bytes)
    throw InputError(name + " is " + std::to_string(size >> 20) + " MiB, more than partreg reads (" +
                     std::to_string(max_bytes >> 20) + " MiB)");
  return size;
}

std::string referenced_file_problem(const std::filesystem::path& referenced,
                                    const std::filesystem::path& input) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(referenced, error)) return "";
  const std::string name = referenced.string();
  // Canonical paths: "..", symbolic links and absolute names are judged by where they really lead.
  const fs::path folder = fs::weakly_canonical(fs::absolute(input, error).parent_path(), error);
  const fs::path target = fs::weakly_canonical(fs::absolute(referenced, error), error);
  const auto [end, rest] = std::mismatch(folder.begin(), folder.end(), target.begin(), target.end());
  if (error || end != folder.end()) return input.string() + " refers to " + name + ", outside its own folder";
  if (!fs::is_regular_file(target, error))
    return input.string() + " refers to " + name + ", not a regular file";
  if (fs::file_size(target, error) > kReadBudget.max_bytes)
    return input.string() + " refers to " + name + ", larger than partreg reads";
  return "";
}

void check_count(const std::string& file, const std::string& what, std::uint64_t count, std::uint64_t limit) {
  if (count > limit)
    throw InputError(file + " declares " + std::to_string(count) + " " + what + ", more than partreg reads (" +
                     std::to_string(limit) + ")");
}

void check_fits(const std::string& file, const std::string& what, std::uint64_t count,
                std::uint64_t min_bytes_each, std::uint64_t available) {
  // Division, not multiplication: a count from a header must not overflow the check meant to catch it.
  if (min_bytes_each > 0 && count > available / min_bytes_each)
    throw InputError(file + " is truncated or its header is wrong: it declares " + std::to_string(count) + " " +
                     what + " (at least " + std::to_string(min_bytes_each) + " bytes each) but only " +
                     std::to_string(available) + " bytes follow its header");
}

}  // namespace partreg::io
