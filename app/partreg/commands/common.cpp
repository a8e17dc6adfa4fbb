#include "partreg/commands/common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/io/output_format.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::app {

core::Points read_points_logged(const std::string& path, std::size_t count, std::uint64_t seed,
                                bool exact_count) {
  std::size_t dropped = 0;
  const bool is_mesh = io::is_mesh_file(path);
  core::Cloud cloud = io::read_as_cloud(path, count, seed, &dropped);
  if (exact_count && !is_mesh) {
    if (static_cast<std::size_t>(cloud.points.rows()) < count)
      throw InputError("asked for " + std::to_string(count) + " points but " + path + " has only " +
                       std::to_string(cloud.points.rows()));
    cloud.points = core::select_rows(cloud.points, core::farthest_point_indices(cloud.points, count));
  }
  std::cerr << "read " << path << ": " << cloud.points.rows() << " points"
            << (is_mesh ? " sampled from the mesh surface" : "");
  if (dropped > 0) std::cerr << " (" << dropped << " NaN or infinite points dropped)";
  std::cerr << '\n';
  return std::move(cloud.points);
}

void write_json_or_stdout(const nlohmann::json& report, const std::string& path, bool log) {
  if (path.empty()) return;
  if (path == "-") {
    std::cout << report.dump(2) << '\n';
    return;
  }
  io::output_format(path, io::OutputKind::json, "JSON output");
  io::write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out << report.dump(2) << '\n';
    if (!out.flush()) throw InputError("cannot write " + path);
  });
  if (log) std::cerr << "wrote " << path << '\n';
}

nlohmann::json settings_json(const std::vector<std::pair<std::string, std::string>>& values,
                             const std::set<std::string>& skip) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [name, value] : values)
    if (!skip.count(name)) json[name] = value;
  return json;
}

nlohmann::json spaces_json(const core::CategoryModel& model) {
  auto values = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  nlohmann::json spaces = nlohmann::json::array();
  for (const core::ShapeSpace& space : model.spaces)
    spaces.push_back({{"name", space.name},
                      {"points", space.point_count()},
                      {"dimensions", space.dimensions()},
                      {"beta", space.beta},
                      {"variances", values(space.variances)},
                      {"explained", values(space.explained_fraction())}});
  return spaces;
}

std::optional<std::vector<double>> parse_numbers(const std::string& text) {
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string field; std::getline(in, field, ',');) {
    std::istringstream number(field);
    double x = 0;
    number >> x;
    if (!number || !number.eof() || !std::isfinite(x)) return std::nullopt;
    values.push_back(x);
  }
  return values;
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  std::stringstream in(text);
  long long width = 0, height = 0;
  char x = 0;
  if (!(in >> width >> x >> height) || !in.eof() || (x != 'x' && x != 'X') || width < 1 || height < 1)
    throw UsageError(option + " takes WIDTHxHEIGHT in pixels (like 1280x960), not '" + text + "'");
  // The renderer's framebuffer and the PNG's pixels are allocated at once: refuse what cannot be drawn.
  constexpr long long kMaxSide = 16384, kMaxPixels = 64LL << 20;
  if (width > kMaxSide || height > kMaxSide || width * height > kMaxPixels)
    throw UsageError(option + " " + text + " is too large: at most " + std::to_string(kMaxSide) +
                     " pixels a side and " + std::to_string(kMaxPixels >> 20) + " megapixels");
  return {static_cast<int>(width), static_cast<int>(height)};
}

CLI::Validator finite_in(double low, double high) {
  auto text_of = [](double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  const std::string range = "[" + text_of(low) + ", " + text_of(high) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(value))
          return "'" + text + "' is not a finite number";
        if (value < low || value > high) return text + " is not in " + range;
        return "";
      },
      "in " + range);
}

CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits =
            !text.empty() && text.size() <= 20 && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || (text.size() == 20 && text > "18446744073709551615"))
          return "'" + text + "' is not a whole number from 0 to 18446744073709551615";
        return "";
      },
      "0 to 2^64-1");
}

CLI::Validator vector3_check(bool nonzero) {
  return CLI::Validator(
      [nonzero](std::string& text) -> std::string {
        try {
          const Eigen::Vector3d v = core::parse_vector3(text, "'" + text + "'");
          if (nonzero && !(v.norm() > 1e-12)) return "'" + text + "' has zero length";
        } catch (const UsageError& error) {
          return error.what();
        }
        return "";
      },
      "X,Y,Z");
}

CLI::Range sample_count_range() { return CLI::Range(std::uint64_t{1}, std::uint64_t{5'000'000}); }

CLI::Range point_count_range() {
  return CLI::Range(std::uint64_t{1}, static_cast<std::uint64_t>(io::kReadBudget.max_points));
}

}  // namespace partreg::app
