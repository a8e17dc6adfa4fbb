// Figure 5 / Figure 7 style plots with cairo: four panels, error against perturbation level, a line per
// variant.
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/eval/report.hpp"

namespace partreg::eval {
namespace {

struct Rgb {
  double r, g, b;
};

// Okabe-Ito colours (colour-blind safe), one per variant in the order of core::Variant's name table (the
// paper's three, then coupled), so a new variant gets the next colour; anything else takes the last.
Rgb variant_colour(const std::string& variant) {
  static constexpr std::array<Rgb, 5> palette{{{0.0, 0.447, 0.698},    // blue
                                               {0.902, 0.624, 0.0},    // orange
                                               {0.0, 0.62, 0.451},     // bluish green
                                               {0.835, 0.369, 0.0},    // vermillion
                                               {0.8, 0.475, 0.655}}};  // reddish purple
  const std::vector<std::string> variants = core::enum_names<core::Variant>();
  const auto index =
      static_cast<std::size_t>(std::find(variants.begin(), variants.end(), variant) - variants.begin());
  return palette[std::min(index, palette.size() - 1)];
}

std::string axis_label(Perturbation kind) {
  switch (kind) {
    case Perturbation::noise:
      return "noise sigma (m, for a 0.3 m object)";
    case Perturbation::outliers:
      return "outlier ratio";
    case Perturbation::rotation:
      return "rotation about x, y, z (rad)";
    case Perturbation::translation:
      return "translation per axis (m, for a 0.3 m object)";
    case Perturbation::yaw:
      return "yaw about the up axis (degrees, after a small tilt)";
    case Perturbation::none:
      break;
  }
  return "";
}

std::string number(double value, int precision) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << value;
  return out.str();
}

struct Box {
  double x, y, width, height;
};

void text(cairo_t* cr, double x, double y, const std::string& s, double size, double align = 0.0) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  cairo_move_to(cr, x - align * extents.width, y);
  cairo_show_text(cr, s.c_str());
}

// A "nice" upper bound for the y axis: 1, 2 or 5 times a power of ten.
double nice_ceiling(double value) {
  if (!(value > 0)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(value)));
  for (double step : {1.0, 2.0, 5.0, 10.0})
    if (step * power >= value) return step * power;
  return 10 * power;
}

// The series of one panel: per variant, (level, mean Eq. 5 x 1e4) with the clean result at level 0.
using Series = std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>>;

Series panel_series(const std::vector<EvalRow>& rows, const std::string& category, bool partial,
                    Perturbation kind) {
  Series series;
  for (const std::string& variant : variants_of(rows)) {
    std::vector<std::pair<double, double>> points;
    const double clean = swept_clean_eq5_per_diagonal2(rows, category, variant, partial);
    // Yaw's first level is 0 (its own clean point, after the tilt): the untilted result is not drawn there.
    if (std::isfinite(clean) && kind != Perturbation::yaw) points.emplace_back(0.0, clean * 1e4);
    const std::vector<double>& levels = sweep_levels(kind);
    for (int level = 0; level < static_cast<int>(levels.size()); ++level) {
      const double mean = mean_eq5_per_diagonal2(rows, category, variant, partial, kind, level);
      if (std::isfinite(mean)) points.emplace_back(shown_level(kind, levels[level]), mean * 1e4);
    }
    if (points.size() > 1) series.emplace_back(variant, points);
  }
  return series;
}

void draw_panel(cairo_t* cr, const Box& box, Perturbation kind, const Series& series) {
  double top = 0.0;
  for (const auto& [variant, points] : series)
    for (const auto& point : points) top = std::max(top, point.second);
  top = nice_ceiling(top * 1.05);
  // The axis ends at the last level run (the wide rotation levels stretch it to pi only when they ran).
  double right = 0.0;
  for (const auto& [variant, points] : series)
    for (const auto& point : points) right = std::max(right, point.first);
  if (!(right > 0.0)) right = shown_level(kind, paper_levels(kind).back());
  const Box plot{box.x + 62, box.y + 30, box.width - 80, box.height - 80};
  auto to_x = [&](double level) { return plot.x + level / right * plot.width; };
  auto to_y = [&](double value) { return plot.y + plot.height - value / top * plot.height; };

  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, box.x + box.width / 2, box.y + 18, core::enum_name(kind), 15, 0.5);
  cairo_set_line_width(cr, 1.0);
  for (int tick = 0; tick <= 4; ++tick) {  // horizontal grid and y labels
    const double value = top * tick / 4;
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, plot.x, to_y(value));
    cairo_line_to(cr, plot.x + plot.width, to_y(value));
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, plot.x - 6, to_y(value) + 4, number(value, top < 4 ? 2 : 1), 11, 1.0);
  }
  std::vector<double> ticks;  // the levels on the axis, thinned to at most six labels
  for (double level : sweep_levels(kind))
    if (shown_level(kind, level) <= right * (1 + 1e-9)) ticks.push_back(shown_level(kind, level));
  const std::size_t every = (ticks.size() + 5) / 6;
  for (std::size_t t = 0; t < ticks.size(); t += every)
    if (ticks[t] > 0.0)
      text(cr, to_x(ticks[t]), plot.y + plot.height + 16, number(ticks[t], kind == Perturbation::yaw ? 0 : 3),
           11, 0.5);
  text(cr, plot.x - 6, plot.y + plot.height + 16, "0", 11, 0.5);
  text(cr, plot.x + plot.width / 2, plot.y + plot.height + 36, axis_label(kind), 12, 0.5);
  cairo_rectangle(cr, plot.x, plot.y, plot.width, plot.height);
  cairo_stroke(cr);

  for (const auto& [variant, points] : series) {
    const Rgb colour = variant_colour(variant);
    cairo_set_source_rgb(cr, colour.r, colour.g, colour.b);
    cairo_set_line_width(cr, 2.2);
    for (std::size_t i = 0; i < points.size(); ++i)
      (i == 0 ? cairo_move_to : cairo_line_to)(cr, to_x(points[i].first), to_y(points[i].second));
    cairo_stroke(cr);
    for (const auto& point : points) {
      cairo_arc(cr, to_x(point.first), to_y(point.second), 3.5, 0, 2 * M_PI);
      cairo_fill(cr);
    }
  }
}

void draw_legend(cairo_t* cr, double x, double y, const std::vector<std::string>& variants) {
  for (const std::string& variant : variants) {
    const Rgb colour = variant_colour(variant);
    cairo_set_source_rgb(cr, colour.r, colour.g, colour.b);
    cairo_set_line_width(cr, 2.2);
    cairo_move_to(cr, x, y - 4);
    cairo_line_to(cr, x + 24, y - 4);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, x + 30, y, variant, 13);
    x += 40 + 9 * variant.size();
  }
}

}  // namespace

bool write_sweep_plot(const std::filesystem::path& path, const std::vector<EvalRow>& rows,
                      const std::string& category, bool partial) {
  std::vector<Series> panels;  // one per sweep that ran, two to a row
  std::vector<Perturbation> kinds;
  for (Perturbation kind : all_sweep_kinds()) {
    Series series = panel_series(rows, category, partial, kind);
    if (series.empty()) continue;
    panels.push_back(std::move(series));
    kinds.push_back(kind);
  }
  if (panels.empty()) return false;
  const int panel_rows = static_cast<int>((panels.size() + 1) / 2);
  const int width = 1000, height = 70 + 345 * panel_rows;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, width / 2.0, 28,
       category + ", " + (partial ? "partial views" : "full views") + ": mean Eq. 5 x 1e4 against the level",
       17, 0.5);
  std::vector<std::string> variants;  // only those this category ran (a category without parts: holistic)
  for (const std::string& variant : variants_of(rows))
    if (std::any_of(panels.begin(), panels.end(), [&](const Series& series) {
          return std::any_of(series.begin(), series.end(),
                             [&](const auto& line) { return line.first == variant; });
        }))
      variants.push_back(variant);
  draw_legend(cr, 24, 56, variants);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Box box{double(k % 2) * width / 2, 70 + double(k / 2) * 345.0, width / 2.0, 345.0};
    draw_panel(cr, box, kinds[k], panels[k]);
  }
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw InputError("cannot write " + path.string() + ": " + cairo_status_to_string(status));
  return true;
}

}  // namespace partreg::eval
