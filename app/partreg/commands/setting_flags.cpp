#include "partreg/commands/setting_flags.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/scene/scene_options.hpp"

namespace partreg::app {
namespace {

// Runs `set` and puts the flag's name before a bad value's message.
template <class Settings>
void set_naming_flag(const core::SettingOption<Settings>& option, Settings& settings, const std::string& value) {
  try {
    option.set(settings, value);
  } catch (const UsageError& error) {
    throw UsageError("--" + option.name + ": " + error.what());
  }
}

template <class Settings>
void add_flags(CLI::App* command, const std::vector<core::SettingOption<Settings>>& options, Settings& settings,
               const std::set<std::string>& skip) {
  const Settings defaults;
  for (const core::SettingOption<Settings>& option : options) {
    if (skip.count(option.name)) continue;
    const std::string flag = "--" + option.name;
    if (option.is_flag) {  // a flag turns on what is off by default, and --no-NAME off what is on
      const bool on = option.get(defaults) == "true";
      command->add_flag_callback(
          on ? "--no-" + option.name : flag,
          [&settings, &option, on] { set_naming_flag(option, settings, on ? "false" : "true"); },
          on ? "do not: " + option.help + " (on by default)" : option.help);
      continue;
    }
    command
        ->add_option_function<std::string>(
            flag, [&settings, &option](const std::string& value) { set_naming_flag(option, settings, value); },
            option.help + " (default " + option.get(defaults) + ")")
        ->type_name(option.value_name);
  }
}

}  // namespace

void add_registration_flags(CLI::App* command, core::RegistrationSettings& settings,
                            const std::set<std::string>& skip) {
  add_flags(command, core::registration_options(), settings, skip);
}

void add_training_flags(CLI::App* command, core::TrainingSettings& settings, const std::set<std::string>& skip) {
  add_flags(command, core::training_options(), settings, skip);
}

void add_scene_flags(CLI::App* command, scene::SceneSettings& settings, const std::set<std::string>& skip) {
  add_flags(command, scene::scene_options(), settings, skip);
}

void add_threads_flag(CLI::App* command, int& threads) {
  command->add_option("--threads", threads, "threads to use, all counted (0 = all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

}  // namespace partreg::app
