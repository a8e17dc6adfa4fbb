#include "partreg/io/warm_start_file.hpp"

#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::io {
namespace {

Eigen::Matrix4d matrix_of(const nlohmann::json& rows) {
  if (!rows.is_array() || rows.size() != 4) throw InputError("a pose must be 4 rows of 4 numbers");
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    const nlohmann::json& row = rows.at(static_cast<std::size_t>(r));
    if (!row.is_array() || row.size() != 4) throw InputError("a pose must be 4 rows of 4 numbers");
    for (int c = 0; c < 4; ++c) {
      const nlohmann::json& value = row.at(static_cast<std::size_t>(c));
      if (!value.is_number()) throw InputError("a pose must be 4 rows of 4 numbers");
      T(r, c) = value.get<double>();
    }
  }
  if (!T.allFinite()) throw InputError("the pose holds a value that is not finite");
  return T;
}

// A result JSON's first space (holistic first where it ran): its pose, and its latent unless the result is
// partwise (a part's latent is not the holistic space's).
core::WarmStart from_result(const nlohmann::json& result) {
  const nlohmann::json& spaces = result.at("spaces");
  if (!spaces.is_array() || spaces.empty()) throw InputError("the result holds no space fit");
  const nlohmann::json& first = spaces.at(0);
  core::WarmStart start;
  start.T_observed_canonical = matrix_of(first.at("T_observed_canonical"));
  if (result.contains("start") && result.at("start").contains("pose_score"))
    start.score = result.at("start").at("pose_score").get<double>();
  if (result.value("variant", "") != "partwise" && first.contains("latent")) {
    const auto latent = first.at("latent").get<std::vector<double>>();
    start.latent = Eigen::Map<const Eigen::VectorXd>(latent.data(), static_cast<Eigen::Index>(latent.size()));
    if (!start.latent.allFinite()) throw InputError("the result's latent holds a value that is not finite");
  }
  return start;
}

// 16 numbers separated by commas or white space, or nothing when `text` is not that.
std::optional<core::WarmStart> from_numbers(const std::string& text) {
  static const std::regex number_list(R"(\s*[-+0-9.eE]+([\s,]+[-+0-9.eE]+){15}\s*)");
  if (!std::regex_match(text, number_list)) return std::nullopt;
  std::string spaced = text;
  for (char& c : spaced)
    if (c == ',') c = ' ';
  std::istringstream in(spaced);
  core::WarmStart start;
  for (int i = 0; i < 16; ++i)
    if (!(in >> start.T_observed_canonical(i / 4, i % 4)))
      throw InputError("--init: cannot read 16 numbers from '" + text + "'");
  if (!start.T_observed_canonical.allFinite()) throw InputError("--init: a number is not finite");
  return start;
}

}  // namespace

core::WarmStart warm_start_from_json(const nlohmann::json& json) {
  try {
    if (json.is_array()) return core::WarmStart{matrix_of(json), {}};
    if (json.is_object() && json.contains("spaces")) return from_result(json);
    if (json.is_object() && json.contains("T_observed_canonical"))
      return core::WarmStart{matrix_of(json.at("T_observed_canonical")), {}};
  } catch (const nlohmann::json::exception& error) {
    throw InputError(std::string("the initial pose: ") + error.what());
  }
  throw InputError("the initial pose is neither a 4x4 array, {\"T_observed_canonical\": ...} nor a result JSON");
}

core::WarmStart read_warm_start(const std::string& text) {
  if (const std::optional<core::WarmStart> numbers = from_numbers(text)) return *numbers;
  std::ifstream in(text);
  if (!in) throw InputError("--init: cannot read " + text + " (neither a file nor 16 numbers)");
  nlohmann::json json;
  try {
    in >> json;
  } catch (const nlohmann::json::exception& error) {
    throw InputError("--init: " + text + " is not JSON: " + error.what());
  }
  try {
    return warm_start_from_json(json);
  } catch (const InputError& error) {
    throw InputError("--init " + text + ": " + error.what());
  }
}

}  // namespace partreg::io
