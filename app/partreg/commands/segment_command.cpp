// `partreg segment (--depth D --intrinsics K [--mask M] | SCENE) [--pick ...] --out DIR`: cut an object out
// of a scene and write what the cut found, for inspection.
#include <iostream>
#include <memory>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/observation_input.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/scene/camera_io.hpp"
#include "partreg/scene/scene_input.hpp"

namespace partreg::app {
namespace {

struct SegmentOptions {
  ObservationInput input;
  std::string out_path;
};

// The object's pixels, where the scene's points have them.
std::optional<scene::PixelMask> object_mask(const scene::SceneCut& cut, const ObservationInput& input) {
  if (input.intrinsics.empty()) return std::nullopt;
  const scene::Intrinsics k = scene::read_intrinsics(input.intrinsics);
  scene::PixelMask mask{k.width, k.height, std::vector<std::uint8_t>(std::size_t(k.width) * k.height, 0)};
  for (int pixel : cut.object.pixel)
    if (pixel >= 0) mask.selected[pixel] = 1;
  return mask;
}

void run_segment(const SegmentOptions& options) {
  if (!options.input.is_scene()) throw UsageError("give a scene cloud, or --depth D --intrinsics K");
  const scene::SceneCut cut = cut_observation(options.input);
  StagedFolder folder(options.out_path);
  const std::filesystem::path dir = folder.staging();
  io::PointAttributes attributes;
  attributes.integers["pixel"] = Eigen::Map<const Eigen::VectorXi>(cut.object.pixel.data(),
                                                                   Eigen::Index(cut.object.pixel.size()));
  io::write_cloud(dir / "object.ply", core::Cloud{cut.object.points, {}}, attributes);
  io::write_cloud(dir / "plane.ply", core::Cloud{cut.plane_points, {}});
  nlohmann::json report = cut_json(cut);
  report["scene"] = options.input.source();
  report["files"] = {{"object", "object.ply"}, {"plane", "plane.ply"}};
  if (const std::optional<scene::PixelMask> mask = object_mask(cut, options.input)) {
    scene::write_mask_png(dir / "object_mask.png", *mask);
    report["files"]["mask"] = "object_mask.png";
  }
  write_json_or_stdout(report, (dir / "segment.json").string(), /*log=*/false);
  folder.commit();
  std::cerr << "wrote " << options.out_path << " (object.ply, plane.ply, segment.json)\n";
}

}  // namespace

void add_segment_command(CLI::App& app) {
  auto o = std::make_shared<SegmentOptions>();
  CLI::App* command = app.add_subcommand(
      "segment", "Cut an object out of a depth image or scene cloud: the support plane, clusters, the choice");
  command->add_option("SCENE", o->input.scene, "scene cloud in the camera frame, metres (or use --depth)");
  add_observation_flags(command, o->input, /*with_scene_flag=*/false);
  command->add_option("--out", o->out_path, "output folder (new or empty)")->required();
  command->callback([o] { run_segment(*o); });
}

}  // namespace partreg::app
