#include "partreg/io/grasps_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io {
namespace {

nlohmann::json parse_file(const std::filesystem::path& path, const char* kind) {
  checked_input_size(path);
  std::ifstream in(path);
  if (!in) throw InputError("cannot open " + std::string(kind) + " file " + path.string());
  nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object())
    throw InputError(path.string() + " is not a JSON " + kind + " file");
  return json;
}

void check_header(const nlohmann::json& json, const std::filesystem::path& path, const char* format) {
  if (json.value("format", "") != format) throw InputError(path.string() + " is not a " + format + " file");
  if (json.value("version", 0) != 1) throw InputError(path.string() + ": unsupported " + format + " version");
}

core::Gripper gripper_of(const nlohmann::json& json) {
  core::Gripper gripper;
  gripper.max_aperture = json.at("max_aperture").get<double>();
  gripper.pad_size = json.value("pad_size", gripper.pad_size);
  gripper.finger_depth = json.value("finger_depth", gripper.finger_depth);
  gripper.friction = json.value("friction", gripper.friction);
  gripper.relative = json.value("relative_to_diagonal", false);
  core::validate(gripper);
  return gripper;
}

nlohmann::json gripper_json(const core::Gripper& gripper) {
  return {{"max_aperture", gripper.max_aperture},
          {"pad_size", gripper.pad_size},
          {"finger_depth", gripper.finger_depth},
          {"friction", gripper.friction},
          {"relative_to_diagonal", gripper.relative}};
}

core::Grasp grasp_of(const nlohmann::json& entry, std::size_t index, const std::string& file) {
  core::Grasp grasp;
  grasp.name = entry.value("name", "grasp_" + std::to_string(index));
  grasp.part = entry.value("part", "");
  for (int i = 0; i < 3; ++i) {
    grasp.position[i] = entry.at("position").at(i).get<double>();
    for (int j = 0; j < 3; ++j) grasp.rotation(i, j) = entry.at("rotation").at(i).at(j).get<double>();
  }
  grasp.width = entry.at("width").get<double>();
  grasp.quality = entry.value("quality", 0.0);
  if (!grasp.position.allFinite() || grasp.position.cwiseAbs().maxCoeff() > 1e12)
    throw InputError(file + ": the position of grasp '" + grasp.name + "' is not a finite number of sensible "
                     "size (|x| <= 1e12)");
  if (!std::isfinite(grasp.width) || grasp.width < 0.0 || grasp.width > 1e12)
    throw InputError(file + ": the width of grasp '" + grasp.name + "' must be a finite length >= 0");
  if (!std::isfinite(grasp.quality)) throw InputError(file + ": grasp '" + grasp.name + "' has a non-finite quality");
  const double error = (grasp.rotation.transpose() * grasp.rotation - Eigen::Matrix3d::Identity()).norm();
  if (!(error < 1e-6) || grasp.rotation.determinant() < 0.0)
    throw InputError(file + ": the rotation of grasp '" + grasp.name + "' is not a proper orthonormal matrix");
  return grasp;
}

}  // namespace

GraspsFile read_grasps_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const nlohmann::json json = parse_file(path, "grasps");
  check_header(json, path, "partreg-grasps");
  GraspsFile read;
  try {
    if (json.contains("gripper")) read.gripper = gripper_of(json.at("gripper"));
    const nlohmann::json& list = json.at("grasps");
    if (!list.is_array()) throw InputError(file + ": \"grasps\" is not a list");
    for (const auto& entry : list) read.grasps.push_back(grasp_of(entry, read.grasps.size(), file));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + " is a malformed grasps file: " + e.what());
  } catch (const UsageError& e) {
    throw InputError(file + ": " + e.what());
  }
  return read;
}

core::Gripper read_gripper_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const nlohmann::json json = parse_file(path, "gripper");
  try {
    if (json.value("format", "") == "partreg-grasps") {
      check_header(json, path, "partreg-grasps");
      if (!json.contains("gripper")) throw InputError(file + " is a grasps file without a gripper");
      return gripper_of(json.at("gripper"));
    }
    check_header(json, path, "partreg-gripper");
    return gripper_of(json);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + " is a malformed gripper file: " + e.what());
  } catch (const UsageError& e) {
    throw InputError(file + ": " + e.what());
  }
}

void write_grasps_file(const std::filesystem::path& path, const std::vector<core::Grasp>& grasps,
                       const std::optional<core::Gripper>& gripper) {
  nlohmann::json list = nlohmann::json::array();
  for (const core::Grasp& grasp : grasps) {
    nlohmann::json rotation = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) rotation.push_back({grasp.rotation(i, 0), grasp.rotation(i, 1), grasp.rotation(i, 2)});
    list.push_back({{"name", grasp.name},
                    {"part", grasp.part},
                    {"position", {grasp.position.x(), grasp.position.y(), grasp.position.z()}},
                    {"rotation", rotation},
                    {"width", grasp.width},
                    {"quality", grasp.quality}});
  }
  nlohmann::json json = {{"format", "partreg-grasps"}, {"version", 1}, {"grasps", list}};
  if (gripper) json["gripper"] = gripper_json(*gripper);
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out << json.dump(2) << '\n';
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

}  // namespace partreg::io
