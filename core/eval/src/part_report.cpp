#include "part_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "partreg/eval/report.hpp"
#include "report_cells.hpp"

namespace partreg::eval::detail {
namespace {

// The parts a category's rows have a per-part figure for (`figures` names the TruthErrors map), first seen
// first.
std::vector<std::string> parts_in(const std::vector<EvalRow>& rows, const std::string& category,
                                  std::map<std::string, double> core::TruthErrors::*figures) {
  std::vector<std::string> parts;
  for (const EvalRow& r : rows)
    if (r.category == category)
      for (const auto& entry : r.errors.*figures)
        if (std::find(parts.begin(), parts.end(), entry.first) == parts.end()) parts.push_back(entry.first);
  return parts;
}

// A part's figure in a per-part map; NaN (left out of means) where the row has none.
double part_figure(const std::map<std::string, double>& figures, const std::string& part) {
  const auto found = figures.find(part);
  return found == figures.end() ? std::nan("") : found->second;
}

// Tables of a figure only some variants' rows carry (`has`), one per view kind: a row per category, a column
// per such variant, each cell `cell_of` the clean rows of that category and variant. Nothing when no row has
// it.
template <class Has, class CellOf>
void clean_figure_tables(std::ostringstream& out, const std::vector<EvalRow>& rows, const std::string& title,
                         Has has, CellOf cell_of) {
  std::vector<std::string> variants;
  for (const std::string& variant : variants_of(rows))
    if (std::any_of(rows.begin(), rows.end(),
                    [&](const EvalRow& r) { return r.variant == variant && has(r); }))
      variants.push_back(variant);
  if (variants.empty()) return;
  for (bool partial : {false, true}) {
    out << "\n" << title << ", " << (partial ? "partial views" : "full views") << "\n\n";
    header_row(out, "category", variants);
    for (const std::string& category : categories_of(rows)) {
      out << "| " << category << " |";
      for (const std::string& variant : variants) {
        std::vector<const EvalRow*> kept;
        for (const EvalRow& r : rows)
          if (r.category == category && r.variant == variant && in_views(r, partial) && has(r) &&
              r.perturbation == Perturbation::none)
            kept.push_back(&r);
        out << ' ' << cell_of(kept) << " |";
      }
      out << "\n";
    }
  }
}

// Mean of `value` over `rows`; NaN for none.
template <class Value>
double mean_over(const std::vector<const EvalRow*>& rows, Value value) {
  double sum = 0.0;
  for (const EvalRow* row : rows) sum += value(*row);
  return rows.empty() ? std::numeric_limits<double>::quiet_NaN() : sum / static_cast<double>(rows.size());
}

}  // namespace

void part_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = variants_of(rows);
  for (const std::string& category : categories_of(rows)) {
    const std::vector<std::string> parts =
        parts_in(rows, category, &core::TruthErrors::part_eq5_per_diagonal2);
    if (parts.size() < 2) continue;
    for (bool partial : {false, true}) {
      out << "\nEq. 5 per part x 1e4, " << category << ", " << (partial ? "partial views" : "full views")
          << " (canonical points of the part to the whole true instance):\n\n";
      header_row(out, "part", variants);
      for (const std::string& part : parts) {
        out << "| " << part << " |";
        for (const std::string& variant : variants) {
          const double mean = clean_mean(rows, category, variant, partial, [&](const EvalRow& r) {
            return part_figure(r.errors.part_eq5_per_diagonal2, part);
          });
          out << ' ' << cell(mean) << " |";
        }
        out << "\n";
      }
    }
  }
}

// Each part against the same part of the truth (where the truth has its own parts), clean observations:
// a row per part and the mean over parts, a column per variant (% of the diagonal).
void own_part_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = variants_of(rows);
  for (const std::string& category : categories_of(rows)) {
    const std::vector<std::string> parts =
        parts_in(rows, category, &core::TruthErrors::own_part_rms_per_diagonal);
    if (parts.empty()) continue;
    for (bool partial : {false, true}) {
      out << "\nEach part against the same part of the truth, " << category << ", "
          << (partial ? "partial views" : "full views")
          << ": symmetric RMS, % of the diagonal (truth_errors.hpp, own_part_rms_per_diagonal):\n\n";
      header_row(out, "part", variants);
      for (const std::string& part : parts) {
        out << "| " << part << " |";
        for (const std::string& variant : variants)
          out << ' '
              << cell(clean_mean(rows, category, variant, partial,
                                 [&](const EvalRow& r) {
                                   return part_figure(r.errors.own_part_rms_per_diagonal, part);
                                 }),
                      100)
              << " |";
        out << "\n";
      }
      out << "| mean over parts |";
      for (const std::string& variant : variants)
        out << ' '
            << cell(clean_mean(rows, category, variant, partial,
                               [](const EvalRow& r) {
                                 return r.errors.own_part_rms_mean_per_diagonal.value_or(std::nan(""));
                               }),
                    100)
            << " |";
      out << "\n";
    }
  }
}

// The seam gap of the part variants on clean observations: the mean gap over boundary points, then the
// largest, each averaged over the rows (% of the model's diagonal).
void seam_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  clean_figure_tables(
      out, rows,
      "Seam gap (core::seam_gap), mean / largest over the boundary points, % of the model's diagonal",
      [](const EvalRow& r) { return r.seam.has_value(); },
      [](const std::vector<const EvalRow*>& kept) {
        return cell(mean_over(kept, [](const EvalRow& r) { return r.seam->mean; }), 100) + " / " +
               cell(mean_over(kept, [](const EvalRow& r) { return r.seam->max; }), 100);
      });
}

// How far the registrations stretched the canonical mesh (the limit on the shape-space grid is 3x):
// the mean over the rows of each row's largest edge stretch, then the largest over the rows.
void stretch_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  clean_figure_tables(
      out, rows,
      "Largest edge stretch of the registered canonical mesh (core::mesh_stretch, deformed / canonical edge "
      "length), mean / largest over the registrations",
      [](const EvalRow& r) { return r.mesh_stretch.has_value(); },
      [](const std::vector<const EvalRow*>& kept) {
        double largest = kept.empty() ? std::numeric_limits<double>::quiet_NaN() : 0.0;
        for (const EvalRow* r : kept) largest = std::max(largest, *r->mesh_stretch);
        return cell(mean_over(kept, [](const EvalRow& r) { return *r.mesh_stretch; }), 1) + " / " +
               cell(largest, 1);
      });
}

}  // namespace partreg::eval::detail
