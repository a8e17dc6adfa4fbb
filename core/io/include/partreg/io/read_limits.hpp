#pragma once
/// \file
/// The reading budget: the largest input partreg accepts. Headers state their counts before the data, so a
/// reader checks them against this budget and against the file's size before it allocates anything; a file
/// beyond them is refused with one line (InputError) instead of exhausting memory or reading for minutes.

#include <cstdint>
#include <filesystem>
#include <string>

namespace partreg::io {

/// Limits on one input file. A depth camera gives about 1e6 points per frame, a scanned mesh a few 1e6
/// faces: the budget is ten to fifty times that.
struct ReadBudget {
  std::uint64_t max_points = 50'000'000;       ///< points or vertices in one file
  std::uint64_t max_faces = 50'000'000;        ///< faces in one mesh file
  std::uint64_t max_bytes = 4ULL << 30;        ///< size of one file (4 GiB)
  std::uint64_t max_header_bytes = 1ULL << 20;  ///< text header of a PLY, PCD or OFF file (1 MiB)
  /// A JSON or CSV document read whole (labels, frames, scripts, evaluation rows; 256 MiB): labels for the
  /// largest cloud take about 100 MiB.
  std::uint64_t max_document_bytes = 256ULL << 20;
  /// Nesting of JSON arrays and objects or XML elements, checked before a recursive parser runs (real
  /// glTF and .vtp files nest fewer than 20 levels).
  int max_nesting = 100;
};

/// The budget every reader uses.
inline constexpr ReadBudget kReadBudget{};

/// The size of `path` in bytes. InputError naming the file when it is missing, not a regular file (after
/// following symbolic links), empty, or larger than the budget.
std::uint64_t checked_input_size(const std::filesystem::path& path);

/// As checked_input_size, with a smaller limit: `max_bytes` (e.g. kReadBudget.max_document_bytes).
std::uint64_t checked_input_size(const std::filesystem::path& path, std::uint64_t max_bytes);

/// For a file that an input names (an OBJ's material library, a glTF's buffer or texture): the reason it is
/// refused, or "" when it is a regular file inside the folder of `input` (or below it) and within the
/// budget. A missing file is not refused here (the library reports it, or does without).
std::string referenced_file_problem(const std::filesystem::path& referenced,
                                    const std::filesystem::path& input);

/// Throws InputError naming `file` when `count` `what` (e.g. "vertices") exceeds `limit`.
void check_count(const std::string& file, const std::string& what, std::uint64_t count, std::uint64_t limit);

/// Throws InputError naming `file` when `count` items of at least `min_bytes_each` bytes cannot fit into the
/// `available` bytes that follow the header (a header claiming more than the file holds).
void check_fits(const std::string& file, const std::string& what, std::uint64_t count,
                std::uint64_t min_bytes_each, std::uint64_t available);

}  // namespace partreg::io
