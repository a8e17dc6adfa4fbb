#pragma once
/// \file
/// Small pieces every command shares: reading any geometry file as points with a log line, and
/// writing a JSON report to a file (atomically) or to stdout.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "partreg/core/space/category_model.hpp"
#include "partreg/core/types.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/result_file.hpp"

namespace partreg::app {

/// A command finished and wrote its outputs, but its result falls short of what was required of it
/// (`register --fail-on`): exit 3.
struct RejectedResult : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads a cloud (NaN points dropped) or samples a mesh to `count` points; logs what it did on stderr. With
/// `exact_count` a cloud is also brought to `count` points (farthest-point sampling), and one with fewer
/// points is an InputError.
core::Points read_points_logged(const std::string& path, std::size_t count, std::uint64_t seed,
                                bool exact_count = false);

/// Writes `report` (indented) to `path` atomically; to stdout when path is "-"; nowhere when path is empty.
/// Logs "wrote PATH" unless `log` is false (files inside a staged folder: their path is not the user's).
void write_json_or_stdout(const nlohmann::json& report, const std::string& path, bool log = true);

using io::matrix_json;

/// Each space of a model: name, points, dimensions, beta, variances and explained fraction per dimension.
nlohmann::json spaces_json(const core::CategoryModel& model);

/// Option values (core/options/setting_option.hpp's option_values) as a JSON object by name, leaving out
/// `skip`.
nlohmann::json settings_json(const std::vector<std::pair<std::string, std::string>>& values,
                             const std::set<std::string>& skip = {});

using io::apply_labels_files;

/// --labels of train and eval (io::apply_labels_files): one or more labels files.
inline constexpr const char* kLabelsHelp =
    "labels files, one per labelled instance (--labels a.json b.json, or repeated): each gives its instance "
    "its parts, which it trains on and, in eval, is scored against; the first file's instance is the "
    "canonical unless --canonical names another of them";

/// "0.3,-1,2" -> {0.3, -1, 2}; empty when any field is not a finite number (the caller names the option).
std::optional<std::vector<double>> parse_numbers(const std::string& text);

/// "1280x960" -> {1280, 960}; UsageError naming `option` for anything else or a side below 1 pixel.
std::pair<int, int> parse_size(const std::string& text, const std::string& option);

using io::StagedFolder;

/// The check every option holding a number of points or samples gets: 1 to the reading budget, so a negative
/// number is a usage error naming the option instead of wrapping around in a size_t.
CLI::Range point_count_range();

/// The check of an option drawing surface samples from a mesh (register, train and eval --samples): 1 to
/// 5,000,000. Five million samples are 120 MB of points; registration and training use thousands, and 5e7
/// held 3 GB for minutes.
CLI::Range sample_count_range();

/// The check of a real-valued option: a finite number in [low, high] (CLI::Range lets NaN through, and "inf"
/// or 1e400 would travel on as infinity).
CLI::Validator finite_in(double low, double high);

/// The check of a seed: a whole number from 0 to 2^64 - 1, written in digits.
CLI::Validator seed_check();

/// The check of an "X,Y,Z" option: three finite numbers (core::parse_vector3); a direction (`nonzero`) must
/// not be 0,0,0.
CLI::Validator vector3_check(bool nonzero);

}  // namespace partreg::app
