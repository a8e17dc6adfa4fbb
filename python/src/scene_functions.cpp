// The module's depth-camera functions: a depth image (a float (H, W) array in metres, or a file) and its
// intrinsics (a dict or a JSON file) cut into an object (segment_depth) and registered in the camera frame
// (register_depth), as `partreg segment` and `partreg register --depth` do.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <filesystem>
#include <thread>
#include <variant>

#include "arrays.hpp"
#include "bindings.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/scene/camera_io.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/scene_options.hpp"
#include "partreg/scene/scene_registration.hpp"
#include "setting_keywords.hpp"

namespace partreg::python {
namespace {

namespace py = pybind11;
using Path = std::filesystem::path;

scene::Intrinsics intrinsics_of(const py::handle& given) {
  if (py::isinstance<py::dict>(given)) {
    // The same keys as the JSON file, read by the same reader (json.dumps refuses NaN: allow_nan=False).
    const std::string text =
        py::str(py::module_::import("json").attr("dumps")(given, py::arg("allow_nan") = false));
    return scene::intrinsics_from_json(nlohmann::json::parse(text), "intrinsics");
  }
  return scene::read_intrinsics(given.cast<Path>());
}

scene::DepthImage depth_of(const py::handle& given, const scene::Intrinsics& k) {
  if (!py::isinstance<py::array>(given)) return scene::read_depth_image(given.cast<Path>(), k);
  const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(given);
  if (!array || array.ndim() != 2) throw UsageError("depth: expected a (height, width) array of metres");
  if (array.shape(0) != k.height || array.shape(1) != k.width)
    throw InputError("the depth image is " + std::to_string(array.shape(1)) + "x" + std::to_string(array.shape(0)) +
                     " pixels but the intrinsics say " + std::to_string(k.width) + "x" + std::to_string(k.height));
  scene::DepthImage depth{k.width, k.height, std::vector<float>(array.data(), array.data() + array.size())};
  for (float& z : depth.metres) {
    if (z < 0) throw InputError("the depth image holds a negative depth");
    if (!std::isfinite(z)) z = 0.0f;
  }
  return depth;
}

std::optional<scene::PixelMask> mask_of(const py::handle& given, const scene::Intrinsics& k) {
  if (given.is_none()) return std::nullopt;
  if (!py::isinstance<py::array>(given)) return scene::read_mask(given.cast<Path>(), k);
  const auto array = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(given);
  if (!array || array.ndim() != 2 || array.shape(0) != k.height || array.shape(1) != k.width)
    throw InputError("mask: expected a (height, width) array the size of the depth image");
  return scene::PixelMask{k.width, k.height, std::vector<std::uint8_t>(array.data(), array.data() + array.size())};
}

scene::Pick pick_of(const py::handle& given) {
  scene::Pick pick;
  if (given.is_none()) return pick;
  const std::vector<double> values = given.cast<std::vector<double>>();
  if (values.size() == 2) pick.pixel = Eigen::Vector2d(values[0], values[1]);
  else if (values.size() == 3) pick.point = Eigen::Vector3d(values[0], values[1], values[2]);
  else throw UsageError("pick: expected (u, v) pixels or (x, y, z) metres");
  return pick;
}

// Keywords that name scene options (scene_options.hpp) are taken out of `keywords` into the settings.
scene::SceneSettings take_scene_keywords(py::kwargs& keywords) {
  scene::SceneSettings settings;
  for (const scene::SceneOption& option : scene::scene_options()) {
    std::string keyword = option.name;
    std::replace(keyword.begin(), keyword.end(), '-', '_');
    if (!keywords.contains(keyword)) continue;
    const py::object value = keywords[keyword.c_str()];
    const std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false")
                                                               : std::string(py::str(value));
    try {
      option.set(settings, text);
    } catch (const UsageError& error) {
      throw UsageError(keyword + ": " + error.what());
    }
    PyDict_DelItemString(keywords.ptr(), keyword.c_str());
  }
  return settings;
}

py::dict cut_dict(const scene::SceneCut& cut) {
  py::list clusters;
  for (const scene::Cluster& c : cut.clusters)
    clusters.append(py::dict(py::arg("points") = c.points,
                             py::arg("centroid") = std::vector<double>{c.centroid.x(), c.centroid.y(), c.centroid.z()},
                             py::arg("off_axis_degrees") = c.off_axis_degrees));
  core::Points object = cut.object.points;
  return py::dict(py::arg("object") = owned_points(std::move(object)),
                  py::arg("pixel") = cut.object.pixel,
                  py::arg("plane") = std::vector<double>{cut.plane[0], cut.plane[1], cut.plane[2], cut.plane[3]},
                  py::arg("up") = std::vector<double>{cut.up.x(), cut.up.y(), cut.up.z()},
                  py::arg("clusters") = clusters, py::arg("chosen") = cut.chosen, py::arg("choice") = cut.choice);
}

scene::SceneCut cut_of(const py::handle& depth, const py::handle& intrinsics, const py::handle& mask,
                       const py::handle& pick, const scene::SceneSettings& settings) {
  const scene::Intrinsics k = intrinsics_of(intrinsics);
  const scene::DepthImage image = depth_of(depth, k);
  const std::optional<scene::PixelMask> selected = mask_of(mask, k);
  const scene::Pick chosen = pick_of(pick);
  py::gil_scoped_release release;
  return scene::cut_scene(scene::depth_view(image, k, selected ? &*selected : nullptr), chosen, settings.segmentation);
}

}  // namespace

void bind_scene_functions(py::module_& m) {
  m.def(
      "segment_depth",
      [](py::handle depth, py::handle intrinsics, py::handle mask, py::handle pick, py::kwargs keywords) {
        const scene::SceneSettings settings = take_scene_keywords(keywords);
        if (!keywords.empty()) throw UsageError("unknown scene setting '" + std::string(py::str(keywords.begin()->first)) + "'");
        return cut_dict(cut_of(depth, intrinsics, mask, pick, settings));
      },
      py::arg("depth"), py::arg("intrinsics"), py::kw_only(), py::arg("mask") = py::none(),
      py::arg("pick") = py::none(),
      "Cuts an object out of a depth image as `partreg segment` does. depth: a (H, W) array of metres (0 or NaN "
      "= none) or a file (16-bit PNG, .npy); intrinsics: a dict with the JSON file's keys or the file; mask: "
      "the object's pixels ((H, W) array or PNG); pick: (u, v) pixels or (x, y, z) metres. Keywords: the scene "
      "options ('-' as '_'). Returns a dict: object (N, 3) camera frame, pixel, plane, up, clusters, chosen, "
      "choice.");
  m.def(
      "register_depth",
      [](const std::shared_ptr<core::CategoryModel>& model, py::handle depth, py::handle intrinsics,
         py::handle mask, py::handle pick, int threads, py::kwargs keywords) {
        if (threads < 0) throw UsageError("threads must be 0 (all cores) or more");
        const scene::SceneSettings settings = take_scene_keywords(keywords);
        const core::RegistrationSettings registration = registration_settings(keywords);
        const scene::SceneCut cut = cut_of(depth, intrinsics, mask, pick, settings);
        py::gil_scoped_release release;
        const core::ThreadBudget budget(threads);
        auto result = std::make_shared<core::RegistrationResult>(
            scene::register_cut(*model, cut, registration, settings.registration));
        py::gil_scoped_acquire acquire;
        py::dict cut_info = cut_dict(cut);
        cut_info["up_axis_degrees"] = scene::up_axis_angle_degrees(*model, *result, cut.up);
        return py::make_tuple(result, cut_info);
      },
      py::arg("model").none(false), py::arg("depth"), py::arg("intrinsics"), py::kw_only(),
      py::arg("mask") = py::none(), py::arg("pick") = py::none(), py::arg("threads") = 0,
      "Cuts the object out of a depth image (as segment_depth) and registers the model to it in the camera "
      "frame (x right, y down, z forward; metres), as `partreg register --depth`: the viewpoint is the camera, "
      "the pose search turns about the table's normal. Keywords: the scene options and the registration "
      "options of register(). Returns (result, cut): the result in the camera frame, the cut as segment_depth "
      "returns it with up_axis_degrees (the registered up axis to the table's normal).");
}

}  // namespace partreg::python
