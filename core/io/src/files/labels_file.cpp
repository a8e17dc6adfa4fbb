#include "partreg/io/labels_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "json_values.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io {

std::array<std::uint8_t, 3> part_color(int index) {
  static const std::array<std::array<std::uint8_t, 3>, 8> okabe_ito = {{{0, 114, 178},
                                                                        {230, 159, 0},
                                                                        {0, 158, 115},
                                                                        {204, 121, 167},
                                                                        {86, 180, 233},
                                                                        {213, 94, 0},
                                                                        {240, 228, 66},
                                                                        {0, 0, 0}}};
  return okabe_ito[static_cast<std::size_t>(index) % okabe_ito.size()];
}

int PartLabels::part_index(const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  names.push_back(name);
  colors.push_back(part_color(static_cast<int>(names.size()) - 1));
  return static_cast<int>(names.size()) - 1;
}

PartLabels read_labels_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  checked_input_size(path, kReadBudget.max_document_bytes);  // a regular file (not a FIFO) within the budget
  std::ifstream in(path);
  if (!in) throw InputError("cannot open labels file " + file);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) throw InputError(file + " is not valid JSON");
  if (!json.is_object()) throw InputError(file + " is not a partreg labels file (not a JSON object)");
  if (!json.contains("format") || json.at("format") != "partreg-labels")
    throw InputError(file + " is not a partreg labels file");
  if (!json.contains("version") || json.at("version") != kLabelsFormatVersion)
    throw InputError(file + " is labels format version " + (json.contains("version") ? json.at("version").dump() : "?") +
                     "; this partreg reads version " + std::to_string(kLabelsFormatVersion));
  try {
    PartLabels labels;
    for (const auto& part : json.at("parts")) {
      labels.names.push_back(part.at("name").get<std::string>());
      // Read as int: nlohmann would wrap 300 into a byte (44) silently.
      const std::vector<int> color = detail::integers_of<int>(part.at("color"));
      if (color.size() != 3) throw InputError(file + ": part '" + labels.names.back() + "' needs three colour channels");
      for (int channel : color)
        if (channel < 0 || channel > 255)
          throw InputError(file + ": part '" + labels.names.back() + "' has a colour channel " +
                           std::to_string(channel) + " outside 0..255");
      labels.colors.push_back({static_cast<std::uint8_t>(color[0]), static_cast<std::uint8_t>(color[1]),
                               static_cast<std::uint8_t>(color[2])});
    }
    if (std::set<std::string>(labels.names.begin(), labels.names.end()).size() != labels.names.size())
      throw InputError(file + " names a part twice");
    const std::string target = json.at("target").get<std::string>();
    if (target != "faces" && target != "points")
      throw InputError(file + ": target must be 'faces' or 'points'");
    labels.target = target == "faces" ? PartLabels::Target::faces : PartLabels::Target::points;
    labels.source = json.contains("source") ? json.at("source").get<std::string>() : "";
    const std::vector<int> values = detail::integers_of<int>(json.at("labels"));
    if (!json.at("count").is_number_unsigned() || json.at("count").get<std::size_t>() != values.size())
      throw InputError(file + " says it has " + json.at("count").dump() + " labels but holds " +
                       std::to_string(values.size()));
    labels.labels =
        Eigen::Map<const Eigen::VectorXi>(values.data(), static_cast<Eigen::Index>(values.size()));
    for (int value : values)
      if (value < -1 || value >= static_cast<int>(labels.names.size()))
        throw InputError(file + " has a label " + std::to_string(value) + " outside its " +
                         std::to_string(labels.names.size()) + " parts");
    return labels;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + " is a malformed labels file: " + e.what());
  }
}

void write_labels_file(const std::filesystem::path& path, const PartLabels& labels) {
  nlohmann::json parts = nlohmann::json::array();
  for (std::size_t i = 0; i < labels.names.size(); ++i)
    parts.push_back({{"name", labels.names[i]}, {"color", labels.colors[i]}});
  const nlohmann::json json = {
      {"format", "partreg-labels"},
      {"version", kLabelsFormatVersion},
      {"source", labels.source},
      {"parts", parts},
      {"target", labels.target == PartLabels::Target::faces ? "faces" : "points"},
      {"count", labels.labels.size()},
      {"labels", std::vector<int>(labels.labels.data(), labels.labels.data() + labels.labels.size())}};
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out << json.dump() << '\n';
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

void check_labels_match(const PartLabels& labels, std::size_t count, const std::string& what) {
  if (static_cast<std::size_t>(labels.labels.size()) != count)
    throw InputError("the labels file has " + std::to_string(labels.labels.size()) +
                     " labels but there are " + std::to_string(count) + " " + what);
}

}  // namespace partreg::io
