#pragma once
/// \file
/// What `partreg render` and `partreg figure` share: option parsing for sizes and vectors, and the figure
/// subcommands (figure_command.cpp), which add_render_commands registers with `render`.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <utility>

#include "partreg/core/geometry/part_selection.hpp"

namespace partreg::app {

/// "x,y,z" -> a vector (the core's parser); UsageError naming the option otherwise.
using core::parse_vector3;

/// Checks a PNG output before any work (io::check_output): UsageError for another extension, InputError
/// ("cannot write X: folder Y does not exist") when its folder is missing.
void check_output_folder(const std::string& path);

/// `partreg figure compare` and `partreg figure space`.
void add_figure_command(CLI::App& app);

}  // namespace partreg::app
