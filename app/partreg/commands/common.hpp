#pragma once
/// \file
/// Small pieces every command shares: reading any geometry file as points with a log line, and
/// writing a JSON report to a file (atomically) or to stdout.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "partreg/core/category_model.hpp"
#include "partreg/core/types.hpp"

namespace partreg::app {

/// Reads a cloud (NaN points dropped) or samples a mesh to `count` points; logs what it did on stderr. With
/// `exact_count` a cloud is also brought to `count` points (farthest-point sampling), and one with fewer
/// points is an InputError.
core::Points read_points_logged(const std::string& path, std::size_t count, std::uint64_t seed,
                                bool exact_count = false);

/// Writes `report` (indented) to `path` atomically; to stdout when path is "-"; nowhere when path is empty.
void write_json_or_stdout(const nlohmann::json& report, const std::string& path);

/// A 4x4 matrix as four JSON rows.
nlohmann::json matrix_json(const Eigen::Matrix4d& matrix);

/// Each space of a model: name, points, dimensions, beta, variances and explained fraction per dimension.
nlohmann::json spaces_json(const core::CategoryModel& model);

}  // namespace partreg::app
