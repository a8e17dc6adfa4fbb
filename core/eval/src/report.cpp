#include "partreg/eval/report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "grasp_report.hpp"
#include "part_report.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/eval/baselines.hpp"
#include "partreg/eval/verdict_report.hpp"
#include "report_cells.hpp"

namespace partreg::eval {
namespace {

using detail::cell;
using detail::clean_mean;
using detail::header_row;
using detail::mean_of;

// One table: a row per category, a column per variant.
template <class Value>
void category_table(std::ostringstream& out, const std::vector<EvalRow>& rows, const std::string& title,
                    bool partial, Value value, double factor, int precision) {
  const std::vector<std::string> variants = variants_of(rows);
  out << "\n" << title << "\n\n| category |";
  for (const std::string& variant : variants) out << ' ' << variant << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < variants.size(); ++i) out << "---|";
  out << "\n";
  for (const std::string& category : categories_of(rows)) {
    out << "| " << category << " |";
    for (const std::string& variant : variants)
      out << ' ' << cell(clean_mean(rows, category, variant, partial, value), factor, precision) << " |";
    out << "\n";
  }
}

}  // namespace

std::vector<std::string> categories_of(const std::vector<EvalRow>& rows) {
  std::vector<std::string> categories;
  for (const EvalRow& row : rows)
    if (std::find(categories.begin(), categories.end(), row.category) == categories.end())
      categories.push_back(row.category);
  return categories;
}

namespace {

// The names of `names` that some row carries, in that order.
std::vector<std::string> present(const std::vector<EvalRow>& rows, const std::vector<std::string>& names) {
  std::vector<std::string> found;
  for (const std::string& name : names)
    if (std::any_of(rows.begin(), rows.end(), [&](const EvalRow& r) { return r.variant == name; }))
      found.push_back(name);
  return found;
}

}  // namespace

std::vector<std::string> variants_of(const std::vector<EvalRow>& rows) {
  return present(rows, core::enum_names<core::Variant>());
}

std::vector<std::string> baselines_of(const std::vector<EvalRow>& rows) {
  return present(rows, core::enum_names<Baseline>());
}

double mean_eq5_per_diagonal2(const std::vector<EvalRow>& rows, const std::string& category,
                              const std::string& variant, bool partial, Perturbation kind, int level_index) {
  return mean_of(
      rows,
      [&](const EvalRow& r) {
        return r.category == category && r.variant == variant && in_views(r, partial) &&
               r.perturbation == kind && r.level_index == level_index;
      },
      [](const EvalRow& r) { return r.errors.eq5_per_diagonal2; });
}

double swept_clean_eq5_per_diagonal2(const std::vector<EvalRow>& rows, const std::string& category,
                                     const std::string& variant, bool partial) {
  std::set<std::pair<std::string, int>> swept;  // (instance, view) pairs that were perturbed
  for (const EvalRow& r : rows)
    if (r.category == category && r.perturbation != Perturbation::none && in_views(r, partial))
      swept.emplace(r.instance, r.view);
  return mean_of(
      rows,
      [&](const EvalRow& r) {
        return r.category == category && r.variant == variant && r.perturbation == Perturbation::none &&
               !r.scene && swept.count({r.instance, r.view}) > 0;
      },
      [](const EvalRow& r) { return r.errors.eq5_per_diagonal2; });
}

double mean_symmetric_rms_per_diagonal(const std::vector<EvalRow>& rows, const std::string& category,
                                       const std::string& method, bool partial) {
  return clean_mean(rows, category, method, partial,
                    [](const EvalRow& r) { return r.errors.symmetric_rms_per_diagonal; });
}

namespace {

void sweep_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = variants_of(rows);
  for (const std::string& category : categories_of(rows))
    for (bool partial : {false, true}) {
      if (std::none_of(rows.begin(), rows.end(), [&](const EvalRow& r) {
            return r.category == category && in_views(r, partial) && r.perturbation != Perturbation::none;
          }))
        continue;
      out << "\nSweeps, " << category << ", " << (partial ? "partial views" : "full views")
          << " (mean Eq. 5 x 1e4; levels in the paper's units for a 0.3 m object, yaw in degrees after a "
          << kYawTilt << " rad tilt):\n\n";
      header_row(out, "perturbation", variants);
      out << "| clean (same observations) |";
      for (const std::string& variant : variants)
        out << ' ' << cell(swept_clean_eq5_per_diagonal2(rows, category, variant, partial)) << " |";
      out << "\n";
      for (Perturbation kind : all_sweep_kinds())
        for (int level = 0; level < static_cast<int>(sweep_levels(kind).size()); ++level) {
          std::ostringstream cells;
          bool any = false;
          for (const std::string& variant : variants) {
            const double mean = mean_eq5_per_diagonal2(rows, category, variant, partial, kind, level);
            any = any || std::isfinite(mean);
            cells << ' ' << cell(mean) << " |";
          }
          if (any)
            out << "| " << core::enum_name(kind) << ' ' << shown_level(kind, sweep_levels(kind)[level])
                << (kind == Perturbation::yaw ? " deg" : "") << " |" << cells.str() << "\n";
        }
    }
}

// The headline figure of every variant on clean views, with its forward and reverse halves (TruthErrors): a
// variant can lead on it by the forward half alone, with parts off their true places (docs/results.md).
void symmetric_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = variants_of(rows);
  for (bool partial : {false, true}) {
    std::ostringstream table;
    bool any = false;
    for (const std::string& category : categories_of(rows)) {
      table << "| " << category << " |";
      for (const std::string& variant : variants) {
        const auto mean = [&](auto value) { return clean_mean(rows, category, variant, partial, value); };
        const double symmetric = mean_symmetric_rms_per_diagonal(rows, category, variant, partial);
        const double forward = mean([](const EvalRow& r) { return r.errors.forward_rms_per_diagonal(); });
        const double reverse = mean([](const EvalRow& r) { return r.errors.reverse_rms_per_diagonal(); });
        any = any || std::isfinite(symmetric);
        table << ' ' << cell(symmetric, 100, 3) << " (" << cell(forward, 100, 2) << " / "
              << cell(reverse, 100, 2) << ") |";
      }
      table << "\n";
    }
    if (!any) continue;
    out << "\nSymmetric RMS distance to the whole true instance (the headline figure, truth_errors.hpp), "
        << "% of the diagonal, " << (partial ? "partial" : "full") << " views (forward / reverse half):\n\n";
    header_row(out, "category", variants);
    out << table.str();
  }
}

// partreg against the baselines on the same clean observations: the symmetric RMS figure of every variant
// and baseline, then each variant's mean over the oracle template's mean.
void baseline_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = variants_of(rows), baselines = baselines_of(rows);
  if (baselines.empty()) return;
  const std::string oracle = core::enum_name(Baseline::oracle_template);
  const bool has_oracle = std::find(baselines.begin(), baselines.end(), oracle) != baselines.end();
  std::vector<std::string> columns = variants;
  columns.insert(columns.end(), baselines.begin(), baselines.end());
  if (has_oracle)
    for (const std::string& variant : variants) columns.push_back(variant + " / " + oracle);
  for (bool partial : {false, true}) {
    out << "\nAgainst the baselines, " << (partial ? "partial views" : "full views")
        << ": mean symmetric RMS, % of the diagonal, and each variant's mean over the oracle template's "
           "(same clean observations):\n\n";
    header_row(out, "category", columns);
    for (const std::string& category : categories_of(rows)) {
      out << "| " << category << " |";
      for (const std::string& method : variants)
        out << ' ' << cell(mean_symmetric_rms_per_diagonal(rows, category, method, partial), 100) << " |";
      for (const std::string& method : baselines)
        out << ' ' << cell(mean_symmetric_rms_per_diagonal(rows, category, method, partial), 100) << " |";
      const double oracle_mean = mean_symmetric_rms_per_diagonal(rows, category, oracle, partial);
      if (has_oracle)
        for (const std::string& variant : variants)
          out << ' '
              << cell(mean_symmetric_rms_per_diagonal(rows, category, variant, partial) / oracle_mean, 1)
              << " |";
      out << "\n";
    }
  }
}

// The depth scenes' figures of one category and variant: scene cuts paired with the hand cut of the same
// scene.
struct SceneFigures {
  int scenes = 0, right = 0;  // scene cuts, and of those the ones that chose the right object
  double overlap_sum = 0.0;   // the scene cuts' overlaps (intersection over union)
  double scene_sum = 0.0, hand_sum = 0.0;
  int registered = 0;  // scenes where both cuts registered (a finite error each)
};

SceneFigures scene_figures(const std::vector<EvalRow>& rows, const std::string& category,
                           const std::string& variant) {
  using Key = std::tuple<std::string, int, int>;                   // instance, fold, scene
  std::map<Key, std::pair<const EvalRow*, const EvalRow*>> pairs;  // scene cut, hand cut
  for (const EvalRow& r : rows)
    if (r.scene && r.category == category && r.variant == variant) {
      auto& pair = pairs[Key{r.instance, r.fold, r.view}];
      (r.scene->cut == CutKind::scene ? pair.first : pair.second) = &r;
    }
  SceneFigures figures;
  for (const auto& [key, pair] : pairs) {
    if (!pair.first) continue;
    ++figures.scenes;
    figures.right += pair.first->scene->precision >= kRightObjectPrecision;
    figures.overlap_sum += pair.first->scene->overlap;
    if (!pair.second) continue;
    const double scene = pair.first->errors.symmetric_rms_per_diagonal;
    const double hand = pair.second->errors.symmetric_rms_per_diagonal;
    if (!std::isfinite(scene) || !std::isfinite(hand)) continue;
    figures.scene_sum += scene, figures.hand_sum += hand, ++figures.registered;
  }
  return figures;
}

// The depth scenes: the scene cut against the same depth image cut by hand, per category and variant.
void scene_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  if (std::none_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.scene.has_value(); })) return;
  out << "\nDepth scenes (eval --scenes): each held-out instance on a table between training instances, "
         "seen by a depth camera; the scene cut (support plane removed, clusters, the one nearest the image "
         "centre) against the same image cut by hand (the object's true mask), each registered about the "
         "table's normal. Right object: at least "
      << kRightObjectPrecision
      << " of the cut's pixels are the object's; overlap: the mean intersection over union of the scene "
         "cut's pixels with the object's measured pixels (below 1: pieces of the object lost, or neighbours "
         "taken). Mean symmetric RMS, % of the diagonal, over the scenes where both cuts registered; scene / "
         "hand is the ratio of the two means.\n\n";
  header_row(out, "category",
             {"variant", "scenes", "right object", "overlap", "scene cut", "hand cut", "scene / hand"});
  for (const std::string& category : categories_of(rows))
    for (const std::string& variant : variants_of(rows)) {
      const SceneFigures f = scene_figures(rows, category, variant);
      if (f.scenes == 0) continue;
      const double scene = f.registered ? f.scene_sum / f.registered : std::nan("");
      const double hand = f.registered ? f.hand_sum / f.registered : std::nan("");
      out << "| " << category << " | " << variant << " | " << f.scenes << " | " << f.right << " ("
          << cell(double(f.right) / f.scenes, 100, 0) << "%) | " << cell(f.overlap_sum / f.scenes, 1, 2)
          << " | " << cell(scene, 100) << " | " << cell(hand, 100) << " | " << cell(scene / hand, 1, 2)
          << " |\n";
    }
}

void timing_table(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  std::vector<std::string> methods = variants_of(rows), baselines = baselines_of(rows);
  methods.insert(methods.end(), baselines.begin(), baselines.end());
  out << "\nTime per registration or baseline (s, mean over every row):\n\n";
  header_row(out, "category", methods);
  for (const std::string& category : categories_of(rows)) {
    out << "| " << category << " |";
    for (const std::string& variant : methods)
      out << ' '
          << cell(mean_of(
                      rows, [&](const EvalRow& r) { return r.category == category && r.variant == variant; },
                      [](const EvalRow& r) { return r.seconds; }),
                  1.0, 3)
          << " |";
    out << "\n";
  }
}

}  // namespace

std::string markdown_report(const std::vector<EvalRow>& rows) {
  std::ostringstream out;
  const std::vector<std::string> variants = variants_of(rows);
  const auto registrations = std::count_if(rows.begin(), rows.end(), [&](const EvalRow& r) {
    return std::find(variants.begin(), variants.end(), r.variant) != variants.end();
  });
  out << "Registrations: " << registrations << " (and " << rows.size() - std::size_t(registrations)
      << " baseline rows, baselines.hpp). Eq. 5 is the paper's error (mean squared distance from each "
         "deformed canonical point to the closest point of the true instance), divided by the square of the "
         "instance's bounding-box diagonal; tables show it x 1e4.\n";
  const auto eq5 = [](const EvalRow& r) { return r.errors.eq5_per_diagonal2; };
  const auto chamfer = [](const EvalRow& r) { return r.errors.chamfer_per_diagonal; };
  category_table(out, rows, "Table 1: mean Eq. 5 x 1e4, fully observed instances", false, eq5, 1e4, 2);
  category_table(out, rows, "Table 2: mean Eq. 5 x 1e4, partial views", true, eq5, 1e4, 2);
  symmetric_tables(out, rows);
  baseline_tables(out, rows);
  category_table(out, rows, "Symmetric Chamfer distance, % of the diagonal, full views", false, chamfer, 100,
                 2);
  category_table(out, rows, "Symmetric Chamfer distance, % of the diagonal, partial views", true, chamfer,
                 100, 2);
  if (std::any_of(rows.begin(), rows.end(),
                  [](const EvalRow& r) { return r.errors.correspondence_per_diagonal; })) {
    const auto correspondence = [](const EvalRow& r) {
      return r.errors.correspondence_per_diagonal ? *r.errors.correspondence_per_diagonal : std::nan("");
    };
    category_table(out, rows, "Correspondence error, % of the diagonal, full views", false, correspondence,
                   100, 2);
    category_table(out, rows, "Correspondence error, % of the diagonal, partial views", true, correspondence,
                   100, 2);
  }
  detail::part_tables(out, rows);
  detail::own_part_tables(out, rows);
  detail::seam_tables(out, rows);
  detail::stretch_tables(out, rows);
  detail::grasp_tables(out, rows);
  verdict_tables(out, rows);
  scene_tables(out, rows);
  sweep_tables(out, rows);
  timing_table(out, rows);
  return out.str();
}

}  // namespace partreg::eval
