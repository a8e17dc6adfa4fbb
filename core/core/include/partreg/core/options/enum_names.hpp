#pragma once
/// \file
/// The names of an enum, written once: one table per enum gives parsing, printing and the list of names for
/// help texts and errors. An enum opts in by specialising EnumNames next to its declaration:
///
///     template <> struct EnumNames<Loss> {
///       static constexpr const char* what = "loss";
///       static constexpr std::array<std::pair<Loss, const char*>, 2> table{{{Loss::squared, "squared"},
///       ...}};
///     };

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "partreg/core/errors.hpp"

namespace partreg::core {

/// Specialise with `what` (what the value is, for errors) and `table` (value, name) pairs.
template <typename Enum>
struct EnumNames;

/// The name of `value` in its enum's table.
template <typename Enum>
std::string enum_name(Enum value) {
  for (const auto& [entry, name] : EnumNames<Enum>::table)
    if (entry == value) return name;
  return "unknown";
}

/// Every name of the enum, in table order.
template <typename Enum>
std::vector<std::string> enum_names() {
  std::vector<std::string> names;
  for (const auto& entry : EnumNames<Enum>::table) names.emplace_back(entry.second);
  return names;
}

/// The names joined by `separator` ("holistic | partwise | hol+part"), for help texts and errors.
template <typename Enum>
std::string enum_choices(const std::string& separator = " | ") {
  std::string joined;
  for (const std::string& name : enum_names<Enum>()) joined += (joined.empty() ? "" : separator) + name;
  return joined;
}

/// The value named `text`; UsageError naming the value and the known names otherwise.
template <typename Enum>
Enum parse_enum(const std::string& text) {
  for (const auto& [entry, name] : EnumNames<Enum>::table)
    if (text == name) return entry;
  throw UsageError(std::string("unknown ") + EnumNames<Enum>::what + " '" + text +
                   "' (known: " + enum_choices<Enum>(", ") + ")");
}

}  // namespace partreg::core
