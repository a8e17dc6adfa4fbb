#pragma once
/// \file
/// Every subcommand of the `partreg` executable registers itself on the CLI11 app through one of these.
/// A command parses its options, calls the libraries and reports; it holds no algorithm of its own.
/// Failures are thrown (partreg::InputError -> exit 1, partreg::UsageError -> exit 2) and turned into
/// one line on stderr by main.cpp.

#include <CLI/CLI.hpp>

namespace partreg::app {

void add_cpd_command(CLI::App& app);
void add_train_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_register_command(CLI::App& app);
void add_label_command(CLI::App& app);
void add_render_commands(CLI::App& app);  ///< `render` and `figure` (headless OSMesa); only with ui/
void add_views_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_grasps_command(CLI::App& app);  ///< `grasps sample` and `grasps check`
void add_segment_command(CLI::App& app);  ///< cut an object out of a depth image or scene cloud
void add_scene_command(CLI::App& app);    ///< render objects on a table as a depth camera sees them

}  // namespace partreg::app
