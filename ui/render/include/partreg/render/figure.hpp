#pragma once
/// \file
/// Figures: grids of rendered panels with titles, row and column labels, and the two kinds partreg makes
/// from its models (see docs/rendering.md): registration comparisons and shape-space walks.

#include <string>
#include <vector>

#include "partreg/core/progress.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/render/headless.hpp"
#include "partreg/render/scene.hpp"

namespace partreg::render {

/// One cell of a figure: a scene and the title written over its top-left corner (may be empty).
struct Panel {
  std::string title;
  Scene scene;
};

/// Panels in rows (row-major, `columns` per row) with optional labels left of each row and above each
/// column.
struct Grid {
  std::vector<Panel> panels;
  int columns = 1;
  std::vector<std::string> row_labels;     ///< empty, or one per row
  std::vector<std::string> column_labels;  ///< empty, or one per column
};

struct FigureSettings {
  int panel_width = 640;   ///< pixels per panel
  int panel_height = 360;  ///< pixels per panel
  Antialiasing antialiasing = Antialiasing::multisample;
  View view = View::iso;
  double fov_y_deg = 20.0;  ///< vertical field of view (degrees); narrow, so side-by-side shapes look alike
  Background background = Background::white;
  int text_scale = 2;         ///< pixels per font unit of titles and labels
  bool shared_camera = true;  ///< one camera fitted to every panel, so sizes compare across panels
};

/// Renders every panel headlessly and lays the grid out with its titles and labels. `progress` hears of each
/// panel rendered (one step each, the panel's title as the line). Throws InputError when the OSMesa context
/// cannot be created.
Image render_grid(const Grid& grid, const FigureSettings& settings,
                  const core::ProgressListener& progress = {});

/// The panel of one registration: the observed points in red and, beside them on the right (as seen from
/// `view`), the deformed canonical coloured by part (its mesh when the model has one, else its points).
Panel comparison_panel(const core::CategoryModel& model, const core::Points& observed,
                       const core::RegistrationResult& result, const std::string& title, View view);

/// The overlay of one registration (the paper's Figures 4 and 6): the deformed canonical coloured by part
/// and the observed points in red in one frame, so where the fit misses the observation shows directly.
Panel overlay_panel(const core::CategoryModel& model, const core::Points& observed,
                    const core::RegistrationResult& result, const std::string& title);

/// The shapes of `space` (holistic or a part's name) along each principal direction, one row per direction,
/// one column per value in `std_devs` (multiples of that direction's standard deviation; others at 0).
/// A part space is shown with the other parts at their mean shape. Shapes are in the category's data frame.
Grid shape_space_grid(const core::CategoryModel& model, const std::string& space,
                      const std::vector<double>& std_devs = {-2.0, -1.0, 0.0, 1.0, 2.0});

}  // namespace partreg::render
