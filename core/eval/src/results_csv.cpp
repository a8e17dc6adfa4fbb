// The evaluation's rows as a results file (results.csv): the layout written, the earlier ones still read.
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "grasp_report.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/eval/report.hpp"
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

}  // namespace

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

}  // namespace partreg::eval
