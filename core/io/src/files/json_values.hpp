#pragma once
// Reading integers from JSON without undefined behaviour (internal to partreg_io): nlohmann's get<int>()
// casts a float such as 1e300 straight to int, which is undefined; these refuse anything but an integer in
// range with nlohmann's own type_error, which every reader turns into its one-line InputError.

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

namespace partreg::io::detail {

template <typename Integer>
Integer integer_of(const nlohmann::json& value) {
  constexpr auto max = static_cast<std::uint64_t>(std::numeric_limits<Integer>::max());
  constexpr auto min = static_cast<std::int64_t>(std::numeric_limits<Integer>::min());
  bool fits = false;
  if (value.is_number_unsigned()) {
    fits = value.get<std::uint64_t>() <= max;
  } else if (value.is_number_integer()) {
    const auto signed_value = value.get<std::int64_t>();
    fits = signed_value >= 0 ? static_cast<std::uint64_t>(signed_value) <= max : signed_value >= min;
  }
  if (!fits)
    throw nlohmann::json::type_error::create(302, "expected an integer in range, not " + value.dump(), &value);
  return value.is_number_unsigned() ? static_cast<Integer>(value.get<std::uint64_t>())
                                    : static_cast<Integer>(value.get<std::int64_t>());
}

template <typename Integer>
std::vector<Integer> integers_of(const nlohmann::json& array) {
  if (!array.is_array()) throw nlohmann::json::type_error::create(302, "expected an array of integers", &array);
  std::vector<Integer> values;
  values.reserve(array.size());
  for (const nlohmann::json& value : array) values.push_back(integer_of<Integer>(value));
  return values;
}

}  // namespace partreg::io::detail
