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
#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/eval/baselines.hpp"
#include "partreg/eval/verdict_report.hpp"

namespace partreg::eval {
namespace {

// A results file is plain CSV: one header line naming the columns, then the rows (what pandas.read_csv and a
// spreadsheet read without options); the run's other facts are in run.json beside it, with the layout's
// number (kRowsFormat: raised when a column changes meaning). Earlier layouts started with a "# partreg
// evaluation rows, format N" line and added columns at the end: 3 the two seam-gap columns, 4 the own-part
// figures, 5 the mesh stretch; plain files add the grasp columns (7), then the verdict and the truth-free
// figures it was judged by (8), then the depth scenes' cut and its overlap and precision against the true
// mask (9). They are still read (their missing figures stay empty).
#define PARTREG_FORMAT_2_COLUMNS                                                                      \
  "category,instance,canonical,fold,variant,view,direction_x,direction_y,direction_z,perturbation,"   \
  "level_index,paper_level,level,diagonal,observed_points,eq5,eq5_per_diagonal2,reverse_eq5,"         \
  "symmetric_rms_per_diagonal,chamfer,chamfer_per_diagonal,correspondence_per_diagonal,part_eq5_per_" \
  "diagonal2,seconds"
#define PARTREG_FORMAT_3_COLUMNS PARTREG_FORMAT_2_COLUMNS ",seam_gap_mean,seam_gap_max"
#define PARTREG_FORMAT_4_COLUMNS \
  PARTREG_FORMAT_3_COLUMNS ",own_part_rms_mean_per_diagonal,own_part_rms_per_diagonal"
#define PARTREG_FORMAT_5_COLUMNS PARTREG_FORMAT_4_COLUMNS ",mesh_stretch_max"
struct CsvFormat {
  const char* line;  ///< the first line of an earlier layout; "" for the current one (no such line)
  const char* header;
  std::size_t columns;
};
#define PARTREG_VERDICT_COLUMNS \
  ",verdict,inlier_share,observed_rms_per_diagonal,latent_distance,pose_ambiguity,scale,refinement_movement"
constexpr std::size_t kFormat2Columns = 24, kFormat3Columns = 26, kFormat4Columns = 28, kFormat5Columns = 29;
constexpr std::size_t kVerdictColumnsStart = kFormat5Columns + detail::kGraspColumnCount;
constexpr std::size_t kVerdictColumnsEnd = kVerdictColumnsStart + 7;
#define PARTREG_SCENE_COLUMNS ",scene_cut,scene_overlap,scene_precision"
constexpr std::size_t kSceneColumnsEnd = kVerdictColumnsEnd + 3;
// The format written first, then the older ones read.
constexpr CsvFormat kFormats[] = {
    {"", PARTREG_FORMAT_5_COLUMNS PARTREG_GRASP_COLUMNS PARTREG_VERDICT_COLUMNS PARTREG_SCENE_COLUMNS,
     kSceneColumnsEnd},
    {"", PARTREG_FORMAT_5_COLUMNS PARTREG_GRASP_COLUMNS PARTREG_VERDICT_COLUMNS, kVerdictColumnsEnd},
    {"", PARTREG_FORMAT_5_COLUMNS PARTREG_GRASP_COLUMNS, kVerdictColumnsStart},
    {"", PARTREG_FORMAT_5_COLUMNS, kFormat5Columns},
    {"# partreg evaluation rows, format 5", PARTREG_FORMAT_5_COLUMNS, kFormat5Columns},
    {"# partreg evaluation rows, format 4", PARTREG_FORMAT_4_COLUMNS, kFormat4Columns},
    {"# partreg evaluation rows, format 3", PARTREG_FORMAT_3_COLUMNS, kFormat3Columns},
    {"# partreg evaluation rows, format 2", PARTREG_FORMAT_2_COLUMNS, kFormat2Columns}};
#undef PARTREG_SCENE_COLUMNS
#undef PARTREG_VERDICT_COLUMNS
#undef PARTREG_FORMAT_5_COLUMNS
#undef PARTREG_FORMAT_4_COLUMNS
#undef PARTREG_FORMAT_3_COLUMNS
#undef PARTREG_FORMAT_2_COLUMNS
constexpr const CsvFormat& kFormat = kFormats[0];

// Part errors in one CSV field: "body=1.2e-05;handle=3.4e-05".
std::string parts_field(const std::map<std::string, double>& parts) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (const auto& [name, value] : parts) out << (out.tellp() > 0 ? ";" : "") << name << '=' << value;
  return out.str();
}

std::map<std::string, double> parse_parts(const std::string& field) {
  std::map<std::string, double> parts;
  std::istringstream in(field);
  for (std::string item; std::getline(in, item, ';');) {
    const auto equals = item.find('=');
    if (equals == std::string::npos) throw std::invalid_argument("part error without '='");
    parts[item.substr(0, equals)] = std::stod(item.substr(equals + 1));
  }
  return parts;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// The verdict's columns (format 8): a registration's verdict and figures; empty for a baseline.
void parse_verdict(EvalRow& row, const std::vector<std::string>& f) {
  const auto field = [&](std::size_t k) { return f[kVerdictColumnsStart + k]; };
  row.verdict = core::parse_enum<core::Verdict>(field(0));
  core::TrustFigures figures;
  figures.inlier_share = std::stod(field(1)), figures.observed_rms = std::stod(field(2));
  figures.latent_distance = std::stod(field(3)), figures.pose_ambiguity = std::stod(field(4));
  figures.scale = std::stod(field(5)), figures.refinement_movement = std::stod(field(6));
  if (row.seam) figures.seam_gap_mean = row.seam->mean, figures.seam_gap_max = row.seam->max;
  if (row.mesh_stretch) figures.mesh_stretch = *row.mesh_stretch;
  row.figures = figures;
}

void write_verdict(std::ostream& out, const EvalRow& r) {
  if (!r.verdict || !r.figures) {
    out << ",,,,,,,";
    return;
  }
  const core::TrustFigures& f = *r.figures;
  out << ',' << core::enum_name(*r.verdict) << ',' << f.inlier_share << ',' << f.observed_rms << ','
      << f.latent_distance << ',' << f.pose_ambiguity << ',' << f.scale << ',' << f.refinement_movement;
}

EvalRow parse_row(const std::vector<std::string>& f) {
  EvalRow row;
  row.category = f[0], row.instance = f[1], row.canonical = f[2], row.fold = std::stoi(f[3]);
  row.variant = f[4], row.view = std::stoi(f[5]);
  row.direction = {std::stod(f[6]), std::stod(f[7]), std::stod(f[8])};
  row.perturbation = core::parse_enum<Perturbation>(f[9]);
  row.level_index = std::stoi(f[10]), row.paper_level = std::stod(f[11]), row.level = std::stod(f[12]);
  row.diagonal = std::stod(f[13]), row.observed_points = std::stoi(f[14]);
  row.errors.diagonal = row.diagonal;
  row.errors.eq5 = std::stod(f[15]), row.errors.eq5_per_diagonal2 = std::stod(f[16]);
  row.errors.reverse_eq5 = std::stod(f[17]), row.errors.symmetric_rms_per_diagonal = std::stod(f[18]);
  row.errors.chamfer = std::stod(f[19]), row.errors.chamfer_per_diagonal = std::stod(f[20]);
  if (!f[21].empty()) row.errors.correspondence_per_diagonal = std::stod(f[21]);
  row.errors.part_eq5_per_diagonal2 = parse_parts(f[22]);
  row.seconds = std::stod(f[23]);
  if (f.size() > kFormat2Columns && !f[24].empty()) {
    row.seam = core::SeamGap{};
    row.seam->mean = std::stod(f[24]);
    row.seam->max = std::stod(f[25]);
  }
  if (f.size() > kFormat3Columns && !f[26].empty()) {
    row.errors.own_part_rms_mean_per_diagonal = std::stod(f[26]);
    row.errors.own_part_rms_per_diagonal = parse_parts(f[27]);
  }
  if (f.size() > kFormat4Columns && !f[28].empty()) row.mesh_stretch = std::stod(f[28]);
  detail::parse_grasp_fields(f, kFormat5Columns, row);
  if (f.size() > kVerdictColumnsStart && !f[kVerdictColumnsStart].empty()) parse_verdict(row, f);
  if (f.size() > kVerdictColumnsEnd && !f[kVerdictColumnsEnd].empty())
    row.scene = SceneCutScore{core::parse_enum<CutKind>(f[kVerdictColumnsEnd]),
                              std::stod(f[kVerdictColumnsEnd + 1]), std::stod(f[kVerdictColumnsEnd + 2])};
  return row;
}

// Mean of `value` over the rows `keep` accepts; NaN for none.
template <class Keep, class Value>
double mean_of(const std::vector<EvalRow>& rows, Keep keep, Value value) {
  double sum = 0.0;
  int count = 0;
  for (const EvalRow& row : rows)
    if (keep(row)) {
      const double v = value(row);
      if (std::isfinite(v)) sum += v, ++count;
    }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

// Mean of `value` over the clean observations of one category and method, full or partial views: what
// every table of clean figures shows in a cell.
template <class Value>
double clean_mean(const std::vector<EvalRow>& rows, const std::string& category, const std::string& method,
                  bool partial, Value value) {
  return mean_of(
      rows,
      [&](const EvalRow& r) {
        return r.category == category && r.variant == method && in_views(r, partial) &&
               r.perturbation == Perturbation::none;
      },
      value);
}

std::string cell(double value, double factor = 1e4, int precision = 2) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << value * factor;
  return out.str();
}

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

void write_rows_csv(const std::filesystem::path& path, const std::vector<EvalRow>& rows) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write " + path.string());
  out << kFormat.header << '\n' << std::setprecision(9);
  for (const EvalRow& r : rows) {
    out << r.category << ',' << r.instance << ',' << r.canonical << ',' << r.fold << ',' << r.variant << ','
        << r.view << ',' << r.direction.x() << ',' << r.direction.y() << ',' << r.direction.z() << ','
        << core::enum_name(r.perturbation) << ',' << r.level_index << ',' << r.paper_level << ',' << r.level
        << ',' << r.diagonal << ',' << r.observed_points << ',' << r.errors.eq5 << ','
        << r.errors.eq5_per_diagonal2 << ',' << r.errors.reverse_eq5 << ','
        << r.errors.symmetric_rms_per_diagonal << ',' << r.errors.chamfer << ','
        << r.errors.chamfer_per_diagonal << ',';
    if (r.errors.correspondence_per_diagonal) out << *r.errors.correspondence_per_diagonal;
    out << ',' << parts_field(r.errors.part_eq5_per_diagonal2) << ',' << r.seconds << ',';
    if (r.seam)
      out << r.seam->mean << ',' << r.seam->max;
    else
      out << ',';
    out << ',';
    if (r.errors.own_part_rms_mean_per_diagonal) out << *r.errors.own_part_rms_mean_per_diagonal;
    out << ',' << parts_field(r.errors.own_part_rms_per_diagonal) << ',';
    if (r.mesh_stretch) out << *r.mesh_stretch;
    out << detail::grasp_fields(r);
    write_verdict(out, r);
    if (r.scene)
      out << ',' << core::enum_name(r.scene->cut) << ',' << r.scene->overlap << ',' << r.scene->precision;
    else
      out << ",,,";
    out << '\n';
  }
  if (!out.flush()) throw InputError("cannot write " + path.string());
}

std::vector<EvalRow> read_rows_csv(const std::filesystem::path& path) {
  // A FIFO or a link to /dev/zero would read forever: a regular file within 256 MiB (io's document budget;
  // eval does not link io).
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw InputError(path.string() +
                     (std::filesystem::exists(path, error) ? " is not a regular file" : ": no such file"));
  if (std::filesystem::file_size(path, error) > (256u << 20))
    throw InputError(path.string() + " is larger than partreg reads (256 MiB)");
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path.string());
  std::string line;
  if (!std::getline(in, line))
    throw InputError(path.string() + " is not a partreg evaluation CSV (it is empty)");
  const bool labelled = line.rfind("# partreg evaluation rows", 0) == 0;  // an earlier layout's first line
  const auto format = std::find_if(std::begin(kFormats), std::end(kFormats), [&](const CsvFormat& known) {
    return labelled ? line == known.line : line == known.header;
  });
  if (labelled && format == std::end(kFormats))
    throw InputError(
        path.string() + " has another format (" + line.substr(2) +
        "; this partreg reads the current one and formats 5, 4, 3 and 2): run the evaluation again");
  if (format == std::end(kFormats))
    throw InputError(path.string() + " is not a partreg evaluation CSV of this version (its header differs)");
  if (labelled && (!std::getline(in, line) || line != format->header))
    throw InputError(path.string() + " is not a partreg evaluation CSV (header differs)");
  const std::size_t columns = format->columns;
  std::vector<EvalRow> rows;
  for (int number = labelled ? 3 : 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split(line);
    try {
      if (fields.size() != columns)
        throw std::invalid_argument("expected " + std::to_string(columns) + " fields");
      rows.push_back(parse_row(fields));
    } catch (const std::exception& e) {
      throw InputError(path.string() + ":" + std::to_string(number) + ": malformed row (" + e.what() + ")");
    }
  }
  return rows;
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

void header_row(std::ostringstream& out, const std::string& first, const std::vector<std::string>& columns) {
  out << "| " << first << " |";
  for (const std::string& column : columns) out << ' ' << column << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << "\n";
}

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
  part_tables(out, rows);
  own_part_tables(out, rows);
  seam_tables(out, rows);
  stretch_tables(out, rows);
  detail::grasp_tables(out, rows);
  verdict_tables(out, rows);
  scene_tables(out, rows);
  sweep_tables(out, rows);
  timing_table(out, rows);
  return out.str();
}

}  // namespace partreg::eval
