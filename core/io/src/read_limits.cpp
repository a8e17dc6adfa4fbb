#include "partreg/io/read_limits.hpp"

#include "partreg/core/errors.hpp"

namespace partreg::io {

std::uint64_t checked_input_size(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    if (std::filesystem::exists(path, error)) throw InputError(name + " is not a regular file");
    throw InputError("no such file: " + name);
  }
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) throw InputError("cannot read " + name + ": " + error.message());
  if (size == 0) throw InputError(name + " is empty");
  if (size > kReadBudget.max_bytes)
    throw InputError(name + " is " + std::to_string(size >> 20) + " MiB, more than partreg reads (" +
                     std::to_string(kReadBudget.max_bytes >> 20) + " MiB)");
  return size;
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
