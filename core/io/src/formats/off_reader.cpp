#include "off_reader.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include <cerrno>
#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io::detail {
namespace {

constexpr std::uint64_t kMaxPolygonCorners = 1024;

// The next line holding something other than a comment, split into words; false at the end of the file.
bool next_words(std::istream& in, std::vector<std::string>& words, std::uint64_t& line_number) {
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    const auto comment = line.find('#');
    if (comment != std::string::npos) line.erase(comment);
    std::istringstream split(line);
    words.clear();
    for (std::string word; split >> word;) words.push_back(word);
    if (!words.empty()) return true;
  }
  return false;
}

bool parse_integer(const std::string& word, long long& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(word.c_str(), &end, 10);
  return end && *end == '\0' && errno == 0;
}

struct Counts {
  std::uint64_t vertices = 0, faces = 0;
};

// "OFF" (or a variant) and "NV NF NE", on one line or two.
Counts read_counts(std::istream& in, const std::string& file, std::uint64_t& line_number) {
  std::vector<std::string> words;
  if (!next_words(in, words, line_number) || words[0].size() < 3 ||
      words[0].compare(words[0].size() - 3, 3, "OFF") != 0)
    throw InputError(file + " is not an OFF file (no OFF header)");
  if (words.size() > 1 && words[1] == "BINARY") throw InputError(file + ": binary OFF files are not supported");
  words.erase(words.begin());
  if (words.empty() && !next_words(in, words, line_number))
    throw InputError(file + ": OFF header has no vertex and face counts");
  long long vertices = -1, faces = -1;
  if (words.size() < 2 || !parse_integer(words[0], vertices) || !parse_integer(words[1], faces) || vertices < 0 ||
      faces < 0)
    throw InputError(file + ": OFF counts must be two non-negative integers");
  check_count(file, "vertices", static_cast<std::uint64_t>(vertices), kReadBudget.max_points);
  check_count(file, "faces", static_cast<std::uint64_t>(faces), kReadBudget.max_faces);
  return {static_cast<std::uint64_t>(vertices), static_cast<std::uint64_t>(faces)};
}

}  // namespace

core::Mesh read_off(const std::filesystem::path& path, std::uint64_t file_size) {
  const std::string file = path.string();
  std::ifstream in(path);
  std::uint64_t line_number = 0;
  const Counts counts = read_counts(in, file, line_number);
  const auto start = static_cast<std::uint64_t>(in.tellg());
  const std::uint64_t available = in && start <= file_size ? file_size - start : 0;
  // "x y z\n" takes at least 6 bytes, "k i ...\n" at least 4: a header claiming more is refused now.
  check_fits(file, "vertices", counts.vertices, 6, available + 1);
  check_fits(file, "faces", counts.faces, 4, available + 1 - counts.vertices * 6);
  auto fail = [&](const std::string& what) {
    throw InputError(file + ":" + std::to_string(line_number) + ": " + what);
  };
  core::Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(counts.vertices), 3);
  std::vector<std::string> words;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    if (!next_words(in, words, line_number))
      fail("the file ends after " + std::to_string(v) + " of its " + std::to_string(counts.vertices) + " vertices");
    if (words.size() < 3) fail("a vertex needs three coordinates");
    for (int d = 0; d < 3; ++d) {
      char* end = nullptr;
      mesh.vertices(v, d) = std::strtod(words[static_cast<std::size_t>(d)].c_str(), &end);
      if (*end != '\0') fail("not a number: '" + words[static_cast<std::size_t>(d)] + "'");
    }
  }
  std::vector<Eigen::Vector3i> triangles;
  for (std::uint64_t f = 0; f < counts.faces; ++f) {
    if (!next_words(in, words, line_number))
      fail("the file ends after " + std::to_string(f) + " of its " + std::to_string(counts.faces) + " faces");
    long long corners = 0;
    if (!parse_integer(words[0], corners) || corners < 1 || static_cast<std::uint64_t>(corners) > kMaxPolygonCorners ||
        words.size() < static_cast<std::size_t>(corners) + 1)
      fail("malformed face");
    std::vector<int> index(static_cast<std::size_t>(corners));
    for (std::size_t k = 0; k < index.size(); ++k) {
      long long value = -1;
      if (!parse_integer(words[k + 1], value) || value < 0 || static_cast<std::uint64_t>(value) >= counts.vertices)
        fail("face index '" + words[k + 1] + "' is not one of the " + std::to_string(counts.vertices) + " vertices");
      index[k] = static_cast<int>(value);
    }
    for (std::size_t k = 2; k < index.size(); ++k) triangles.emplace_back(index[0], index[k - 1], index[k]);
    check_count(file, "triangles", triangles.size(), kReadBudget.max_faces);
  }
  mesh.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) mesh.faces.row(static_cast<Eigen::Index>(f)) = triangles[f];
  return mesh;
}

}  // namespace partreg::io::detail
