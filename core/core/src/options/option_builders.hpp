#pragma once
// Builders for the tables of options (internal to partreg_core): the text each kind of value is read from
// and written as, shared by registration_options.cpp and training_options.cpp so that a number, a switch or
// a vector reads the same way whichever settings it belongs to.

#include <Eigen/Core>
#include <string>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/options/setting_option.hpp"

namespace partreg::core::detail {

/// The shortest text that reads back as exactly `value` (0.03, not 0.029999999999999999).
std::string text_of(double value);
/// A finite number in [low, high] read from `text`; UsageError naming `what` otherwise.
double real_in(const std::string& text, const std::string& what, double low, double high);
/// A whole number in [low, high] read from `text`; UsageError naming `what` otherwise.
int integer_in(const std::string& text, const std::string& what, int low, int high);
/// true/1/on/yes or false/0/off/no; UsageError naming `what` otherwise.
bool boolean(const std::string& text, const std::string& what);
/// "X,Y,Z" with finite components; UsageError naming `what` otherwise.
Eigen::Vector3d finite_vector(const std::string& text, const std::string& what);
/// An up axis: finite_vector's "X,Y,Z" of non-zero length; UsageError otherwise. Registration's and
/// training's up options both read it so.
Eigen::Vector3d up_axis_in(const std::string& text);
/// "X,Y,Z" as finite_vector reads it back exactly.
std::string vector_text(const Eigen::Vector3d& v);

/// Options on one field of `Settings`: `field(settings)` returns a reference to it.
template <class Settings>
struct OptionOn {
  using Option = SettingOption<Settings>;

  template <typename Enum, typename Field>
  static Option choice(std::string name, std::string help, Field field) {
    return {name,
            enum_choices<Enum>("|"),
            std::move(help),
            false,
            [field](Settings& s, const std::string& v) { field(s) = parse_enum<Enum>(v); },
            [field](const Settings& s) { return enum_name(field(s)); }};
  }

  template <typename Field>
  static Option real(std::string name, std::string help, double low, double high, Field field) {
    return {name,
            "X",
            std::move(help),
            false,
            [=](Settings& s, const std::string& v) { field(s) = real_in(v, name, low, high); },
            [=](const Settings& s) { return text_of(field(s)); }};
  }

  template <typename Field>
  static Option whole(std::string name, std::string help, int low, int high, Field field) {
    return {name,
            "N",
            std::move(help),
            false,
            [=](Settings& s, const std::string& v) { field(s) = integer_in(v, name, low, high); },
            [=](const Settings& s) { return std::to_string(field(s)); }};
  }

  template <typename Field>
  static Option flag(std::string name, std::string help, Field field) {
    return {name,
            "",
            std::move(help),
            true,
            [=](Settings& s, const std::string& v) { field(s) = boolean(v, name); },
            [=](const Settings& s) { return std::string(field(s) ? "true" : "false"); }};
  }
};

}  // namespace partreg::core::detail
