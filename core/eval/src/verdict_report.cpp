#include "partreg/eval/verdict_report.hpp"

#include <iomanip>
#include <sstream>
#include <tuple>

#include "partreg/eval/baselines.hpp"

namespace partreg::eval {
namespace {

// What identifies one observation: the rows of its variants and its baselines share it.
using ObservationKey = std::tuple<std::string, std::string, int, int, int, int>;

ObservationKey key_of(const EvalRow& row) {
  return {row.category, row.instance, row.fold, row.view, static_cast<int>(row.perturbation), row.level_index};
}

std::string share(int part, int whole) {
  if (whole == 0) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(0) << 100.0 * part / whole << "%";
  return out.str();
}

}  // namespace

std::map<std::string, VerdictTally> tally_verdicts(const std::vector<EvalRow>& rows) {
  const std::string oracle = core::enum_name(Baseline::oracle_template);
  std::map<ObservationKey, double> oracle_rms;
  for (const EvalRow& row : rows)
    if (row.variant == oracle) oracle_rms[key_of(row)] = row.errors.symmetric_rms_per_diagonal;
  std::map<std::string, VerdictTally> tallies;
  for (const EvalRow& row : rows) {
    // Depth-scene rows have no oracle (no baselines run on them), and their view numbers scenes, not views.
    if (row.scene) continue;
    const auto found = oracle_rms.find(key_of(row));
    if (!row.verdict || found == oracle_rms.end()) continue;
    const bool bad = row.errors.symmetric_rms_per_diagonal > kBadRatio * found->second;
    const bool flagged = *row.verdict != core::Verdict::good;
    for (const std::string& category : {std::string(), row.category}) {
      VerdictTally& tally = tallies[category];
      (bad ? tally.bad : tally.good) += 1;
      (bad ? tally.bad_flagged : tally.good_flagged) += flagged ? 1 : 0;
      tally.failed += *row.verdict == core::Verdict::failed ? 1 : 0;
    }
  }
  return tallies;
}

void verdict_tables(std::ostream& out, const std::vector<EvalRow>& rows) {
  const std::map<std::string, VerdictTally> tallies = tally_verdicts(rows);
  if (tallies.empty()) return;
  out << "\n### The verdict against the truth\n\nA registration is bad when its symmetric RMS is above " << kBadRatio
      << "x the oracle template's on the same observation; flagged: a verdict of doubtful or failed "
         "(core/registration/verdict.hpp).\n\n| category | bad | bad flagged | good | good flagged | failed |\n|---|---|---|---|---|---|\n";
  for (const auto& [category, t] : tallies) {
    if (category.empty()) continue;
    out << "| " << category << " | " << t.bad << " | " << t.bad_flagged << " (" << share(t.bad_flagged, t.bad)
        << ") | " << t.good << " | " << t.good_flagged << " (" << share(t.good_flagged, t.good) << ") | "
        << t.failed << " |\n";
  }
  const VerdictTally& all = tallies.at("");
  out << "| all | " << all.bad << " | " << all.bad_flagged << " (" << share(all.bad_flagged, all.bad) << ") | "
      << all.good << " | " << all.good_flagged << " (" << share(all.good_flagged, all.good) << ") | " << all.failed
      << " |\n";
}

}  // namespace partreg::eval
