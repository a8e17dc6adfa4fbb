#include "partreg/ui/panels.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "partreg/ui/executor.hpp"
#include "partreg/ui/labelling.hpp"

namespace partreg::ui {
namespace {

void emit(std::vector<Command>& out, const std::string& verb, std::vector<std::string> arguments = {}) {
  out.push_back(make_command(verb, std::move(arguments)));
}

// File names only: full paths make screenshots depend on where the files are.
std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// A text field backed by a std::string (ImGui 1.86 without imgui_stdlib's resize callback); `hint` shows
// in grey while it is empty.
bool input_text(const char* label, std::string& text, const char* hint = "") {
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer), "%s", text.c_str());
  const bool changed = ImGui::InputTextWithHint(label, hint, buffer, sizeof(buffer));
  if (changed) text = buffer;
  return changed;
}

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3f", value);
  return buffer;
}

// Faces inside a box, on one side of a plane or inside a sphere (the mesh's units) go to the current part,
// as the script's select_box, select_plane and select_sphere verbs do.
void region_selection(PanelState& panel, std::vector<Command>& out) {
  ImGui::Separator();
  static constexpr const char* labels[] = {"Box", "Plane (the normal's side)", "Sphere"};
  static_assert(std::size(labels) == std::size(kRegionVerbs));
  ImGui::Combo("Region", &panel.region_tool, labels, static_cast<int>(std::size(labels)));
  const char* verb = kRegionVerbs[panel.region_tool];
  input_text("##region", panel.region_numbers, find_verb(verb)->synopsis.c_str());
  ImGui::SameLine();
  if (ImGui::Button("Select")) emit(out, verb, {panel.region_numbers});
}

void labelling_panel(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  const LabelDocument& document = state.labelling;
  if (!document.loaded()) {
    ImGui::TextWrapped("Open a canonical mesh to label (any format assimp reads), or a labelled model.");
    return;
  }
  ImGui::TextWrapped("%s", file_name(document.mesh_path).c_str());
  ImGui::Text("%d faces%s", static_cast<int>(document.mesh.faces.rows()),
              document.dirty ? "  (unsaved)" : "");
  ImGui::Separator();
  ImGui::Text("Tool");
  int tool = static_cast<int>(panel.tool);
  ImGui::RadioButton("Orbit", &tool, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Paint", &tool, 1);
  ImGui::SameLine();
  ImGui::RadioButton("Fill", &tool, 2);
  panel.tool = static_cast<Tool>(tool);
  float radius = static_cast<float>(document.brush_radius_px);
  if (ImGui::SliderFloat("Brush (px)", &radius, 2.0f, 80.0f, "%.0f"))
    emit(out, "brush", {number_text(radius)});
  ImGui::Separator();
  const std::vector<int> counts = part_face_counts(document);
  for (std::size_t p = 0; p < document.labels.names.size(); ++p) {
    ImGui::PushID(static_cast<int>(p));
    const auto& rgb = document.labels.colors[p];
    float color[3] = {rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f};
    if (ImGui::ColorEdit3("##color", color, ImGuiColorEditFlags_NoInputs)) {
      emit(out, "recolor_part",
           {document.labels.names[p], std::to_string(static_cast<int>(color[0] * 255.0f + 0.5f)),
            std::to_string(static_cast<int>(color[1] * 255.0f + 0.5f)),
            std::to_string(static_cast<int>(color[2] * 255.0f + 0.5f))});
    }
    ImGui::SameLine();
    const std::string label = document.labels.names[p] + "  (" + std::to_string(counts[p]) + " faces)";
    if (ImGui::Selectable(label.c_str(), static_cast<int>(p) == document.current_part))
      emit(out, "select_part", {document.labels.names[p]});
    ImGui::PopID();
  }
  ImGui::TextDisabled("unlabelled: %d faces", counts.back());
  input_text("##new", panel.new_part);
  ImGui::SameLine();
  if (ImGui::Button("Create part")) emit(out, "create_part", {panel.new_part});
  if (document.current_part >= 0) {
    const std::string& current = document.labels.names[static_cast<std::size_t>(document.current_part)];
    input_text("##rename", panel.rename_to);
    ImGui::SameLine();
    if (ImGui::Button("Rename")) emit(out, "rename_part", {current, panel.rename_to});
    if (ImGui::Button("Delete part")) emit(out, "delete_part", {current});
    for (const std::string& other : document.labels.names) {
      if (other == current) continue;
      ImGui::SameLine();
      if (ImGui::Button(("Merge into " + other).c_str())) emit(out, "merge_part", {current, other});
    }
  }
  region_selection(panel, out);
  ImGui::Separator();
  if (ImGui::Button("Undo")) emit(out, "undo");
  ImGui::SameLine();
  if (ImGui::Button("Redo")) emit(out, "redo");
  input_text("##labels", panel.labels_path);
  ImGui::SameLine();
  if (ImGui::Button("Save labels")) emit(out, "save_labels", {panel.labels_path});
  ImGui::Separator();
  input_text("Dataset", panel.dataset_path);
  input_text("##model", panel.model_out);
  ImGui::SameLine();
  if (ImGui::Button("Train"))
    out.push_back(make_command("train", {panel.dataset_path}, {{"out", panel.model_out}}));
}

// Where each training instance lies on the slider just drawn: a short mark under the frame, the shown
// instance's darker. `frame_width` is the slider's frame (without its label); sliders span -3..+3 sd.
void slider_ticks(const ShapeDocument& shapes, const core::ShapeSpace& space, int k, float frame_width) {
  const double sd = std::sqrt(space.variances[k]);
  if (!(sd > 0.0)) return;
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (Eigen::Index i = 0; i < space.training_latents.rows(); ++i) {
    const double value = std::clamp(space.training_latents(i, k) / sd, -3.0, 3.0);
    const float x = low.x + static_cast<float>((value + 3.0) / 6.0) * frame_width;
    const bool shown = i == shapes.shown_instance;
    draw->AddLine(ImVec2(x, high.y - (shown ? 6.0f : 4.0f)), ImVec2(x, high.y),
                  shown ? IM_COL32(20, 20, 20, 255) : IM_COL32(90, 90, 90, 200), shown ? 2.0f : 1.0f);
  }
}

// The training instances: choosing one draws it beside the sliders' shape, with its name over it.
void instance_list(const AppState& state, std::vector<Command>& out) {
  const ShapeDocument& shapes = state.shapes;
  const std::vector<std::string>& names = shapes.model->training.instances;
  ImGui::Text("Training instances (compare)");
  const float rows = static_cast<float>(std::min<std::size_t>(names.size(), 6));
  if (ImGui::BeginListBox("##instances",
                          ImVec2(-1.0f, rows * ImGui::GetTextLineHeightWithSpacing() + 4.0f))) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      const bool shown = static_cast<int>(i) == shapes.shown_instance;
      if (ImGui::Selectable(names[i].c_str(), shown)) emit(out, "show_instance", {shown ? "none" : names[i]});
    }
    ImGui::EndListBox();
  }
  if (shapes.shown_instance < 0) return;
  const std::string& name = names[static_cast<std::size_t>(shapes.shown_instance)];
  if (ImGui::Button("Sliders to it")) emit(out, "instance_latent", {name});
  ImGui::SameLine();
  if (ImGui::Button("Hide")) emit(out, "show_instance", {"none"});
  if (const std::optional<InstanceBeside> beside = instance_beside(state)) {
    const Eigen::Vector2d at = project(state.view, state.viewport, beside->label_anchor);
    if (!at.allFinite()) return;
    const ImVec2 size = ImGui::CalcTextSize(name.c_str());
    ImGui::GetBackgroundDrawList()->AddText(
        ImVec2(static_cast<float>(at.x()) - 0.5f * size.x, static_cast<float>(at.y()) - 1.5f * size.y),
        IM_COL32(40, 40, 40, 255), name.c_str());
  }
}

void shape_panel(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  const ShapeDocument& shapes = state.shapes;
  if (!shapes.loaded()) {
    ImGui::TextWrapped("Load a model (.prm) to explore its shape spaces.");
    return;
  }
  const core::CategoryModel& model = *shapes.model;
  ImGui::TextWrapped("%s: %s", model.category.c_str(), file_name(shapes.model_path).c_str());
  const core::ShapeSpace& current = model.spaces[static_cast<std::size_t>(shapes.space)];
  if (ImGui::BeginCombo("Space", current.name.c_str())) {
    for (std::size_t s = 0; s < model.spaces.size(); ++s)
      if (ImGui::Selectable(model.spaces[s].name.c_str(), static_cast<int>(s) == shapes.space))
        emit(out, "space", {model.spaces[s].name});
    ImGui::EndCombo();
  }
  ImGui::Text("Principal directions (standard deviations)");
  const Eigen::VectorXd explained = current.explained_fraction();
  const Eigen::VectorXd& values = shapes.std_devs[static_cast<std::size_t>(shapes.space)];
  for (int k = 0; k < current.dimensions(); ++k) {
    char label[64];
    std::snprintf(label, sizeof(label), "PC%d  %4.1f%%", k + 1, 100.0 * explained[k]);
    float value = static_cast<float>(values[k]);
    const float frame_width = ImGui::CalcItemWidth();
    if (ImGui::SliderFloat(label, &value, -3.0f, 3.0f, "%+.2f"))
      emit(out, "set_latent", {current.name, std::to_string(k + 1), number_text(value)});
    slider_ticks(shapes, current, k, frame_width);
  }
  if (shapes.animated_space == shapes.space) {
    if (ImGui::Button("Stop")) emit(out, "animate", {"off"});
  } else {
    ImGui::InputInt("##animated", &panel.animated_dimension);
    panel.animated_dimension = std::clamp(panel.animated_dimension, 1, std::max(1, current.dimensions()));
    ImGui::SameLine();
    if (ImGui::Button("Animate"))
      emit(out, "animate", {current.name, std::to_string(panel.animated_dimension)});
  }
  if (ImGui::Button("Reset")) emit(out, "reset_latents", {current.name});
  ImGui::SameLine();
  if (ImGui::Button("Random sample")) emit(out, "sample_latents", {std::to_string(panel.sample_seed++)});
  ImGui::TextDisabled("%d training instances, %d canonical points",
                      static_cast<int>(model.training.instances.size()),
                      static_cast<int>(model.canonical.rows()));
  ImGui::Separator();
  instance_list(state, out);
}

// The evaluation's tools on the observation: a partial view of 42, and the paper's perturbations.
void evaluation_tools(PanelState& panel, std::vector<Command>& out) {
  ImGui::InputInt("##view", &panel.view_index);
  panel.view_index = std::clamp(panel.view_index, 0, 41);
  ImGui::SameLine();
  if (ImGui::Button("Partial view")) emit(out, "partial_view", {std::to_string(panel.view_index)});
  const char* kinds[] = {"noise", "outliers", "rotation", "translation"};
  ImGui::Combo("##kind", &panel.perturbation, kinds, 4);
  ImGui::InputFloat("##level", &panel.perturbation_level, 0.0f, 0.0f, "%.3f");
  ImGui::SameLine();
  if (ImGui::Button("Perturb"))
    emit(out, "perturb", {kinds[panel.perturbation], number_text(panel.perturbation_level)});
}

// A combo box over an enum's names (its EnumNames table); `index` is the chosen entry.
template <typename Enum>
void enum_combo(const char* label, int& index) {
  constexpr auto& table = core::EnumNames<Enum>::table;
  std::array<const char*, table.size()> names{};
  for (std::size_t i = 0; i < table.size(); ++i) names[i] = table[i].second;
  ImGui::Combo(label, &index, names.data(), static_cast<int>(names.size()));
}

template <typename Enum>
std::string name_at(int index) {
  return core::EnumNames<Enum>::table.at(static_cast<std::size_t>(index)).second;
}

// The variant and the objective; Register emits them as the register command's options.
void registration_options(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  if (panel.variant < 0) panel.variant = enum_index(state.registration.settings.variant);
  enum_combo<core::Variant>("Variant", panel.variant);
  enum_combo<core::Direction>("Closest points", panel.direction);
  enum_combo<core::Loss>("Loss", panel.loss);
  if (state.registration.viewpoint) ImGui::Checkbox("Use the viewpoint", &panel.use_viewpoint);
  if (!ImGui::Button("Register")) return;
  std::vector<std::pair<std::string, std::string>> options = registration_panel_options(state, panel);
  const std::string variant = options.front().second;
  options.erase(options.begin());
  Command command = make_command("register", {variant}, std::move(options));
  if (state.registration.viewpoint && !panel.use_viewpoint) command.options.emplace_back("viewpoint", "none");
  out.push_back(std::move(command));
}

void registration_panel(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  const RegistrationDocument& registration = state.registration;
  if (registration.observed.rows() == 0) {
    ImGui::TextWrapped("Load a model and an observed cloud or mesh to register.");
    return;
  }
  ImGui::TextWrapped("%s", file_name(registration.observed_path).c_str());
  ImGui::Text("%d observed points", static_cast<int>(registration.observed.rows()));
  registration_options(state, panel, out);
  evaluation_tools(panel, out);
  input_text("##frames", panel.frames_path, "frames file (grasps)");
  ImGui::SameLine();
  if (ImGui::Button("Load frames")) emit(out, "load_frames", {panel.frames_path});
  if (!registration.result) return;
  const core::RegistrationResult& result = *registration.result;
  const int steps = static_cast<int>(result.history.size());
  ImGui::Separator();
  ImGui::Text("%s: %d steps, %.2f s", core::enum_name(result.variant).c_str(), steps, result.seconds);
  int step = registration.step + 1;
  if (ImGui::SliderInt("Step", &step, 0, steps)) emit(out, "goto_step", {std::to_string(step)});
  if (ImGui::Button("<")) emit(out, "step", {"-1"});
  ImGui::SameLine();
  if (ImGui::Button(">")) emit(out, "step", {"1"});
  ImGui::SameLine();
  if (ImGui::Button("Last")) emit(out, "goto_step", {"last"});
  std::vector<float> costs;
  for (const core::HistoryStep& h : result.history) costs.push_back(static_cast<float>(h.cost));
  ImGui::PlotLines("Cost", costs.data(), static_cast<int>(costs.size()), 0, nullptr, FLT_MAX, FLT_MAX,
                   ImVec2(0.0f, 60.0f));
  if (registration.step >= 0) {
    const core::HistoryStep& h = result.history[static_cast<std::size_t>(registration.step)];
    ImGui::Text("space %s  cost %.4g  at %.3f s", h.space.c_str(), h.cost, h.seconds);
  }
  ImGui::Text("fit: mean %.4g, p90 %.4g (data units)", result.fit.mean, result.fit.p90);
  if (result.fit.strays > 0) ImGui::Text("%d observed points left out as strays", result.fit.strays);
  const core::TrustFigures& f = result.figures;
  ImGui::Text("verdict: %s", core::enum_name(result.assessment.verdict).c_str());
  for (const std::string& reason : result.assessment.reasons) ImGui::BulletText("%s", reason.c_str());
  ImGui::TextWrapped("inliers %.1f%%, RMS %.2f%%, latent %.2f sd, pose ambiguity %.3g, scale %.3g", 100.0 * f.inlier_share,
              100.0 * f.observed_rms, f.latent_distance, f.pose_ambiguity, f.scale);
  input_text("##result", panel.result_folder);
  ImGui::SameLine();
  if (ImGui::Button("Save result")) emit(out, "save_result", {panel.result_folder});
}

// Open: a model, a mesh or a cloud (load decides by the file); in the registration tab with a model loaded,
// the file is the observation.
void file_row(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  input_text("##open", panel.open_path, "model, mesh or cloud file");
  ImGui::SameLine();
  if (!ImGui::Button("Open") || panel.open_path.empty()) return;
  const bool observation = state.mode == Mode::registration && state.shapes.loaded();
  emit(out, observation ? "load_observed" : "load", {panel.open_path});
}

}  // namespace

std::vector<std::pair<std::string, std::string>> registration_panel_options(const AppState& state,
                                                                            const PanelState& panel) {
  const int variant = panel.variant < 0 ? enum_index(state.registration.settings.variant) : panel.variant;
  return {{"variant", name_at<core::Variant>(variant)},
          {"direction", name_at<core::Direction>(panel.direction)},
          {"loss", name_at<core::Loss>(panel.loss)}};
}

void draw_panels(const AppState& state, PanelState& panel, std::vector<Command>& out) {
  const ImGuiIO& io = ImGui::GetIO();
  const float width = static_cast<float>(state.viewport.panel_width);
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y), ImGuiCond_Always);
  const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                 ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
  ImGui::Begin("partreg", nullptr, fixed);
  file_row(state, panel, out);
  // Programmatic mode changes (scripts, loads) select their tab once.
  const bool mode_changed = panel.first_frame || panel.shown_mode != state.mode;
  panel.first_frame = false;
  panel.shown_mode = state.mode;
  if (ImGui::BeginTabBar("modes")) {
    const std::pair<Mode, const char*> tabs[] = {{Mode::labelling, "Labelling"},
                                                 {Mode::shape_space, "Shape space"},
                                                 {Mode::registration, "Registration"}};
    for (const auto& [mode, title] : tabs) {
      const ImGuiTabItemFlags flags = mode_changed && mode == state.mode ? ImGuiTabItemFlags_SetSelected : 0;
      if (!ImGui::BeginTabItem(title, nullptr, flags)) continue;
      if (mode != state.mode && !mode_changed) emit(out, "mode", {core::enum_name(mode)});
      if (mode == Mode::labelling) labelling_panel(state, panel, out);
      if (mode == Mode::shape_space) shape_panel(state, panel, out);
      if (mode == Mode::registration) registration_panel(state, panel, out);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  // A running training's and registration's progress (whichever tab is open), the screenshot row and the
  // status line at the bottom of the column.
  const float rows =
      1.0f + (state.training.running ? 1.0f : 0.0f) + (state.registering.running ? 1.0f : 0.0f);
  ImGui::SetCursorPosY(io.DisplaySize.y - ImGui::GetTextLineHeightWithSpacing() * 2.5f -
                       ImGui::GetFrameHeightWithSpacing() * rows);
  for (const JobProgress* job : {&state.training, &state.registering})
    if (job->running)
      ImGui::ProgressBar(static_cast<float>(job->fraction), ImVec2(-1.0f, 0.0f), job->line.c_str());
  input_text("##screenshot", panel.screenshot_path);
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) emit(out, "screenshot", {panel.screenshot_path});
  ImGui::Separator();
  if (state.status_is_error)
    ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1.0f), "%s", state.status.c_str());
  else
    ImGui::TextWrapped("%s", state.status.c_str());
  ImGui::End();
  if (panel.confirm_quit) {
    ImGui::OpenPopup("Unsaved labels");
    panel.confirm_quit = false;
  }
  if (ImGui::BeginPopupModal("Unsaved labels", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("The labels have unsaved changes.");
    if (ImGui::Button("Save")) {
      emit(out, "save_labels", {panel.labels_path});
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Quit without saving")) panel.confirmed_quit = true;
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

}  // namespace partreg::ui
