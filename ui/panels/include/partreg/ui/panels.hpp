#pragma once
/// \file
/// The Dear ImGui panels: a column on the left with a tab per mode (labelling, shape space, registration)
/// and a status line. Panels read the state and only emit commands; they never change the state.

#include <string>
#include <utility>
#include <vector>

#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"

namespace partreg::ui {

/// What the mouse does in the viewport (chosen in the labelling panel).
enum class Tool { orbit, paint, fill };

/// Position of `value` in its EnumNames table: the entry a combo box over that table shows.
template <typename Enum>
int enum_index(Enum value) {
  const auto& table = core::EnumNames<Enum>::table;
  for (std::size_t i = 0; i < table.size(); ++i)
    if (table[i].first == value) return static_cast<int>(i);
  return 0;
}

/// The labelling panel's region selections, by the script verbs they emit (their synopsis is the field's
/// hint).
inline constexpr const char* kRegionVerbs[] = {"select_box", "select_plane", "select_sphere"};

/// The panels' own editing state: text being typed, the tool, the last mode shown. Not app state.
struct PanelState {
  Tool tool = Tool::orbit;
  std::string new_part = "handle";
  std::string rename_to;
  std::string labels_path = "labels.json";
  std::string screenshot_path = "partreg-gui.png";
  std::string open_path;                 ///< the file the Open button loads (model, mesh or cloud)
  std::string frames_path;               ///< frames attached to the canonical (registration tab)
  std::string result_folder = "result";  ///< where Save result writes
  /// The registration panel's choices (indices into their EnumNames tables) start at the library's defaults:
  /// the settings whose values the options table reports to `partreg register` and Python.
  int direction = enum_index(core::RegistrationSettings{}.objective.direction);
  int loss = enum_index(core::RegistrationSettings{}.objective.loss);
  bool use_viewpoint = true;             ///< count only canonical points facing the known viewpoint
  int variant = -1;            ///< index into EnumNames<Variant>; -1 = the app's settings' (last used)
  int region_tool = 0;         ///< index into kRegionVerbs
  std::string region_numbers;  ///< the selected region tool's numbers (data units)
  int sample_seed = 1;
  int animated_dimension = 1;            ///< the principal direction the Animate button sweeps (from 1)
  std::string dataset_path = "dataset";  ///< folder the Train button trains on
  std::string model_out = "model.prm";   ///< where it writes the model
  int view_index = 0;                    ///< partial view to take (of 42)
  int perturbation = 0;                  ///< 0 noise, 1 outliers, 2 rotation, 3 translation
  float perturbation_level = 0.01f;      ///< in the paper's units
  Mode shown_mode = Mode::labelling;
  bool first_frame = true;
  bool confirm_quit = false;    ///< the window asked to close with unsaved labels: ask the user
  bool confirmed_quit = false;  ///< the user chose to quit without saving
};

/// The registration options the panel's Register button sends, by the options table's names and in its text
/// ("direction" -> "symmetric"): the variant (the app's settings' unless one was chosen), direction and loss.
std::vector<std::pair<std::string, std::string>> registration_panel_options(const AppState& state,
                                                                            const PanelState& panel);

/// Builds the panels for this ImGui frame (between ImGui::NewFrame and ImGui::Render) and appends what the
/// user asked for to `emitted`.
void draw_panels(const AppState& state, PanelState& panel, std::vector<Command>& emitted);

}  // namespace partreg::ui
