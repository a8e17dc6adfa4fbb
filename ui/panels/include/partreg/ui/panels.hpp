#pragma once
/// \file
/// The Dear ImGui panels: a column on the left with a tab per mode (labelling, shape space, registration)
/// and a status line. Panels read the state and only emit commands; they never change the state.

#include <string>
#include <vector>

#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"

namespace partreg::ui {

/// What the mouse does in the viewport (chosen in the labelling panel).
enum class Tool { orbit, paint, fill };

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
  int direction = 1;                     ///< index into EnumNames<Direction>: observed (the default)
  int loss = 1;                          ///< index into EnumNames<Loss>: huber (the default)
  bool use_viewpoint = true;             ///< count only canonical points facing the known viewpoint
  int variant = -1;                      ///< 0 holistic, 1 partwise, 2 hol+part; -1 = the last registration's
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

/// Builds the panels for this ImGui frame (between ImGui::NewFrame and ImGui::Render) and appends what the
/// user asked for to `emitted`.
void draw_panels(const AppState& state, PanelState& panel, std::vector<Command>& emitted);

}  // namespace partreg::ui
