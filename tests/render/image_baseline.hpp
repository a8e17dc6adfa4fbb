#pragma once
/// \file
/// Comparing a rendered image with its committed baseline (tests/baselines/NAME.png).
///
/// A pixel is bad when any channel differs by more than `channel_tolerance`; the comparison fails when the
/// share of bad pixels exceeds `max_bad_fraction`. On failure the actual image and a diff image (bad pixels
/// red over a faded copy of the baseline) are written to <build>/render_failures/NAME.actual.png and
/// NAME.diff.png. A missing baseline fails and writes <build>/render_failures/NAME.png for a person to
/// inspect and copy into tests/baselines/. With PARTREG_UPDATE_BASELINES=1 in the environment, the baseline
/// itself is (re)written instead, and the test still fails so that nobody mistakes it for a pass.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "partreg/render/image.hpp"
#include "partreg/render/renderer.hpp"

namespace partreg::testing {

inline std::filesystem::path baseline_path(const std::string& name) {
  return std::filesystem::path(PARTREG_SOURCE_DIR) / "tests" / "baselines" / (name + ".png");
}

inline std::filesystem::path failure_folder() {
  const std::filesystem::path folder = std::filesystem::path(PARTREG_BINARY_DIR) / "render_failures";
  std::filesystem::create_directories(folder);
  return folder;
}

/// The share of pixels with a channel further than `channel_tolerance` apart (1 for different sizes).
inline double bad_pixel_fraction(const render::Image& a, const render::Image& b, int channel_tolerance,
                                 render::Image* diff = nullptr) {
  if (a.width != b.width || a.height != b.height) return 1.0;
  if (diff) *diff = render::Image(a.width, a.height);
  std::size_t bad = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      int worst = 0;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
      if (worst > channel_tolerance) ++bad;
      if (diff) {
        std::uint8_t* out = diff->pixel(x, y);
        if (worst > channel_tolerance) {
          out[0] = 255, out[1] = 0, out[2] = 0;
        } else {
          for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(191 + b.pixel(x, y)[c] / 4);
        }
        out[3] = 255;
      }
    }
  return static_cast<double>(bad) / (static_cast<double>(a.width) * a.height);
}

inline void expect_matches_baseline(const render::Image& actual, const std::string& name,
                                    int channel_tolerance = 24, double max_bad_fraction = 0.003) {
  const std::filesystem::path baseline = baseline_path(name);
  const char* update = std::getenv("PARTREG_UPDATE_BASELINES");
  if (update && std::string(update) == "1") {
    render::write_png(baseline, actual);
    ADD_FAILURE() << "rewrote the baseline " << baseline << " (PARTREG_UPDATE_BASELINES=1): look at it";
    return;
  }
  if (!std::filesystem::exists(baseline)) {
    const std::filesystem::path written = failure_folder() / (name + ".png");
    render::write_png(written, actual);
    ADD_FAILURE() << "no baseline " << baseline << "; wrote the image to " << written
                  << ": look at it and copy it there if it shows what its name says";
    return;
  }
  const render::Image expected = render::read_png(baseline);
  render::Image diff;
  const double fraction = bad_pixel_fraction(actual, expected, channel_tolerance, &diff);
  if (fraction <= max_bad_fraction) return;
  const std::filesystem::path folder = failure_folder();
  render::write_png(folder / (name + ".actual.png"), actual);
  if (!diff.empty()) render::write_png(folder / (name + ".diff.png"), diff);
  ADD_FAILURE() << name << ": " << 100.0 * fraction << "% of the pixels differ by more than "
                << channel_tolerance << " (allowed " << 100.0 * max_bad_fraction << "%; sizes "
                << actual.width << "x" << actual.height << " and " << expected.width << "x" << expected.height
                << "); wrote " << (folder / (name + ".actual.png")) << " and "
                << (folder / (name + ".diff.png"));
}

/// Draws `scene` at full quality, then as an interactive frame, then at full quality again with the same
/// renderer: the interactive frame differs from the full one but stays its likeness (at most `max_bad` of its
/// pixels off by more than 48 in a channel), and the next full frame is the first one again.
inline void expect_interactive_likeness(render::Renderer& renderer, const render::Scene& scene,
                                        const render::Camera& camera, double max_bad) {
  const render::Image full = renderer.render(scene, camera);
  renderer.draw(scene, camera, render::FrameQuality::interactive);
  const render::Image interactive = renderer.read_pixels();
  EXPECT_NE(interactive.rgba, full.rgba);
  EXPECT_LT(bad_pixel_fraction(interactive, full, 48), max_bad);
  EXPECT_EQ(renderer.render(scene, camera).rgba, full.rgba);
}

}  // namespace partreg::testing
