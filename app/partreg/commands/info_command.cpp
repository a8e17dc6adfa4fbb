// `partreg info MODEL`: what a category model holds.
#include <iostream>
#include <memory>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/space_walk.hpp"
#include "partreg/io/model_file.hpp"

namespace partreg::app {
namespace {

// The largest edge stretch of each space's walk over -2..+2 standard deviations (null without a mesh).
nlohmann::json stretch_json(const core::CategoryModel& model) {
  if (model.canonical_mesh.faces.rows() == 0) return nullptr;
  nlohmann::json figures = nlohmann::json::array();
  for (const core::SpaceStretch& figure : core::space_grid_stretch(model))
    figures.push_back({{"space", figure.space},
                       {"max_stretch", figure.max_stretch},
                       {"direction", figure.direction},
                       {"std_devs", figure.std_devs}});
  return figures;
}

// How far apart the part spaces put the parts of their own training shapes (null without parts).
nlohmann::json training_seam_gap_json(const core::CategoryModel& model) {
  if (!model.has_parts()) return nullptr;
  const core::SeamGap gap = core::training_seam_gap(model);
  return {{"mean", gap.mean}, {"max", gap.max}, {"points", gap.points}};
}

nlohmann::json describe(const core::CategoryModel& model) {
  const auto& record = model.training;
  return {{"category", model.category},
          {"parts", model.part_names},
          {"up", {model.up.x(), model.up.y(), model.up.z()}},
          {"canonical_points", model.canonical.rows()},
          {"mesh_vertices", model.canonical_mesh.vertices.rows()},
          {"mesh_faces", model.canonical_mesh.faces.rows()},
          {"scale", model.normalization.scale},
          {"centre",
           {model.normalization.centre.x(), model.normalization.centre.y(), model.normalization.centre.z()}},
          {"spaces", spaces_json(model)},
          {"stretch", stretch_json(model)},
          {"training_seam_gap", training_seam_gap_json(model)},
          {"training", io::training_record_json(record)}};
}

void print(const nlohmann::json& info) {
  std::cout << "category " << info["category"].get<std::string>() << ": " << info["canonical_points"]
            << " canonical points, mesh " << info["mesh_vertices"] << " vertices / " << info["mesh_faces"]
            << " faces, diagonal " << info["scale"] << " (data units)\n";
  std::cout << "parts: " << (info["parts"].empty() ? std::string("none") : info["parts"].dump())
            << "; up axis " << info["up"].dump() << '\n';
  for (const auto& space : info["spaces"]) {
    std::cout << "space " << space["name"].get<std::string>() << ": " << space["points"] << " points, "
              << space["dimensions"] << " dimensions, explained variance:";
    double cumulative = 0.0;
    for (const auto& fraction : space["explained"]) {
      cumulative += fraction.get<double>();
      std::cout << ' ' << std::round(fraction.get<double>() * 1000) / 10 << '%';
    }
    std::cout << " (total " << std::round(cumulative * 1000) / 10 << "%)\n";
  }
  for (const auto& figure : info["stretch"])
    std::cout << "space " << figure["space"].get<std::string>() << ": largest mesh edge stretch "
              << std::round(figure["max_stretch"].get<double>() * 100) / 100 << "x its canonical length "
              << "over -2..+2 sd (PC" << figure["direction"].get<int>() + 1 << " at "
              << figure["std_devs"].get<double>() << " sd)\n";
  if (!info["training_seam_gap"].is_null())
    std::cout << "part spaces at the training shapes: seam gap mean "
              << std::round(info["training_seam_gap"]["mean"].get<double>() * 1e4) / 100 << "%, largest "
              << std::round(info["training_seam_gap"]["max"].get<double>() * 1e4) / 100
              << "% of the diagonal (seam band " << info["training"]["seam_band"] << ")\n";
  const auto& training = info["training"];
  if (!training["seam_weight"].is_null())
    std::cout << "coupled seam weight " << training["seam_weight"] << " ("
              << training["seam_weight_choice"].get<std::string>() << ")\n";
  std::cout << "trained on " << training["instances"].size() << " instances " << training["instances"].dump()
            << ", canonical " << training["canonical"].get<std::string>() << " ("
            << training["canonical_choice"].get<std::string>() << "), beta " << training["beta"]
            << ", lambda " << training["lambda"] << '\n';
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto model_path = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  CLI::App* command =
      app.add_subcommand("info", "Describe a category model: parts, spaces, explained variance");
  command->add_option("MODEL", *model_path, "model file")->required();
  command->add_flag("--json", *as_json, "print JSON instead of text");
  command->callback([model_path, as_json] {
    const nlohmann::json info = describe(io::read_model(*model_path));
    if (*as_json)
      std::cout << info.dump(2) << '\n';
    else
      print(info);
  });
}

}  // namespace partreg::app
