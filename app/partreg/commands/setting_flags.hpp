#pragma once
/// \file
/// The command line's face of the option tables (core/registration/registration_options.hpp,
/// core/training/training_options.hpp) and of the thread budget: every command that registers or trains adds
/// its flags here, so `register`, `eval` and `figure compare` take the same registration flags, and `train`
/// and `eval` the same training flags, with the same defaults.

#include <CLI/CLI.hpp>
#include <set>
#include <string>

#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/scene/scene_options.hpp"

namespace partreg::app {

/// Adds `--NAME` for every registration option except those in `skip` (a command that sets one itself, as
/// eval's per-row variant). Values are parsed into `settings` while the command line is read; a bad value is
/// a UsageError naming the flag.
void add_registration_flags(CLI::App* command, core::RegistrationSettings& settings,
                            const std::set<std::string>& skip = {});

/// Adds `--NAME` for every training option except those in `skip`, as add_registration_flags does.
void add_training_flags(CLI::App* command, core::TrainingSettings& settings,
                        const std::set<std::string>& skip = {});

/// Adds `--NAME` for every scene option (the cut of a depth image or scene cloud, scene_options.hpp).
void add_scene_flags(CLI::App* command, scene::SceneSettings& settings, const std::set<std::string>& skip = {});

/// Adds `--threads N` (0 = all cores): the command's thread budget (core/parallel.hpp).
void add_threads_flag(CLI::App* command, int& threads);

}  // namespace partreg::app
