#pragma once
/// \file
/// What an evaluation run leaves behind: every row as CSV (readable again, so shards and categories can be
/// merged), Markdown tables laid out like the paper's Tables 1 and 2 plus the sweeps behind its Figures 5
/// and 7, and those figures as PNG plots (cairo).

#include <filesystem>
#include <string>
#include <vector>

#include "partreg/eval/protocol.hpp"

namespace partreg::eval {

/// The layout of results.csv (its columns and their meaning), recorded in run.json beside it: raised when a
/// column changes meaning. The CSV itself is plain: a header line, then the rows.
inline constexpr int kRowsFormat = 9;

/// Writes rows as CSV: one header line naming the columns, then one line per row (pandas.read_csv reads it
/// without options). Throws InputError when the file cannot be written.
void write_rows_csv(const std::filesystem::path& path, const std::vector<EvalRow>& rows);

/// Reads rows written by write_rows_csv, or by an earlier partreg (a "# partreg evaluation rows, format N"
/// first line, N 2 to 5). InputError naming the file and line for anything else.
std::vector<EvalRow> read_rows_csv(const std::filesystem::path& path);

/// The mean of Eq. 5 (normalised by the squared diagonal) over the rows that match; NaN when none match.
/// `partial`: partial views (true) or the full view (false). `level_index` -1 selects the clean rows.
double mean_eq5_per_diagonal2(const std::vector<EvalRow>& rows, const std::string& category,
                              const std::string& variant, bool partial,
                              Perturbation kind = Perturbation::none, int level_index = -1);

/// The clean (unperturbed) mean Eq. 5 over only the observations that the sweeps perturbed, so that it is
/// the sweeps' level 0; NaN when there are no sweeps.
double swept_clean_eq5_per_diagonal2(const std::vector<EvalRow>& rows, const std::string& category,
                                     const std::string& variant, bool partial);

/// The mean symmetric RMS figure (TruthErrors::symmetric_rms_per_diagonal) of a variant or a baseline over
/// the clean rows that match; NaN when none match. `partial` as for mean_eq5_per_diagonal2.
double mean_symmetric_rms_per_diagonal(const std::vector<EvalRow>& rows, const std::string& category,
                                       const std::string& method, bool partial);

/// The Markdown report: Tables 1 and 2 (mean Eq. 5 x 1e4 on full and partial views, per category and
/// variant), the symmetric RMS figure of every variant and baseline with each variant's ratio to the oracle
/// template (ratio of the means), Chamfer, per-part (against the whole truth, and against the same part of
/// a truth with parts) and correspondence errors, seam gaps, the sweeps per category (the
/// variants only), and run times.
std::string markdown_report(const std::vector<EvalRow>& rows);

/// A Figure 5 (full views) or Figure 7 (partial views) style plot for one category: four panels (noise,
/// outliers, rotation, translation), mean Eq. 5 against the level, one line per variant. Returns false (and
/// writes nothing) when the rows hold no sweep for it; throws InputError when the PNG cannot be written.
bool write_sweep_plot(const std::filesystem::path& path, const std::vector<EvalRow>& rows,
                      const std::string& category, bool partial);

/// The categories, variants and baselines present in rows: categories in first-seen order, variants in the
/// paper's order, baselines in Baseline order (baselines.hpp).
std::vector<std::string> categories_of(const std::vector<EvalRow>& rows);
std::vector<std::string> variants_of(const std::vector<EvalRow>& rows);
std::vector<std::string> baselines_of(const std::vector<EvalRow>& rows);

}  // namespace partreg::eval
