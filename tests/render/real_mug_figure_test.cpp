// Figures of the real mug model with parts (ShapeNet mugs, committed handle labels), against committed
// baselines: the handle's shape space at -2 and +2 standard deviations (joined to the body at every cell:
// the parts' fields are blended across the seam) and the overlay comparison of `figure compare`.
#include <gtest/gtest.h>

#include "image_baseline.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/render/figure.hpp"
#include "support/labelled_mugs.hpp"

namespace partreg {
namespace {

constexpr const char* kHeldOut = "6aec84952a5ffcf33f60d03e1cb068dc";  // the walkthrough's unseen mug

render::FigureSettings panels(render::View view, int width, int height) {
  render::FigureSettings settings;
  settings.panel_width = width;
  settings.panel_height = height;
  settings.view = view;
  return settings;
}

// Training takes about 25 s, so one test draws both figures from one model. Training and registration are
// bit-for-bit repeatable (the parallel sums run in a fixed order), so the baselines hold to the renderer's
// usual tolerance.

TEST(RealMugFigures, HandleSpaceAtTwoSdAndOverlayComparison) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("mugs"));
  const core::CategoryModel model = testing::train_labelled_mugs(kHeldOut);
  const render::Grid space = render::shape_space_grid(model, "handle", {-2.0, 2.0});
  testing::expect_matches_baseline(render::render_grid(space, panels(render::View::side, 240, 200)),
                                   "figure_real_mug_handle_space_2sd");

  const core::Points observed =
      io::read_as_cloud(testing::shared_data(std::string("mugs/") + kHeldOut + ".obj"), 2000, 1).points;
  render::Grid overlays;
  for (core::Variant variant : {core::Variant::partwise, core::Variant::hol_part}) {
    core::RegistrationSettings settings;
    settings.variant = variant;
    const core::RegistrationResult result = core::register_observation(model, observed, settings);
    overlays.panels.push_back(render::overlay_panel(model, observed, result, core::enum_name(variant)));
  }
  overlays.columns = 2;
  testing::expect_matches_baseline(render::render_grid(overlays, panels(render::View::iso, 360, 300)),
                                   "figure_real_mug_overlay");
}

}  // namespace
}  // namespace partreg
