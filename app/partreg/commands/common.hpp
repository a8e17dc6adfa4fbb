#pragma once
/// \file
/// Small pieces every command shares: reading any geometry file as points with a log line, and
/// writing a JSON report to a file (atomically) or to stdout.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

#include "partreg/core/types.hpp"

namespace partreg::app {

/// Reads a cloud (NaN points dropped) or samples a mesh to `mesh_samples` points; logs what it did on stderr.
core::Points read_points_logged(const std::string& path, std::size_t mesh_samples, std::uint64_t seed);

/// Writes `report` (indented) to `path` atomically; to stdout when path is "-"; nowhere when path is empty.
void write_json_or_stdout(const nlohmann::json& report, const std::string& path);

}  // namespace partreg::app
