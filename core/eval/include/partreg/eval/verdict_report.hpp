#pragma once
/// \file
/// The verdict (core/registration/verdict.hpp) set against the truth on the evaluation's rows: a registration
/// is bad when its symmetric RMS error is above `kBadRatio` times the oracle template's on the same
/// observation (the best rigidly aligned training instance, baselines.hpp); a flag is a verdict of doubtful
/// or failed.

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "partreg/eval/protocol.hpp"

namespace partreg::eval {

/// Above this many times the oracle template's symmetric RMS on the same observation, a registration is bad.
inline constexpr double kBadRatio = 1.5;

/// How the verdicts of a set of registrations stand against the truth.
struct VerdictTally {
  int bad = 0, bad_flagged = 0;    ///< registrations the truth calls bad; of those, flagged
  int good = 0, good_flagged = 0;  ///< the others; of those, flagged (false alarms)
  int failed = 0;                  ///< verdicts of failed, bad or good
};

/// Tallies by category ("" holds every category) over the registration rows with a verdict and an oracle
/// template row on the same observation (same category, instance, fold, view, perturbation and level).
std::map<std::string, VerdictTally> tally_verdicts(const std::vector<EvalRow>& rows);

/// The markdown table of tally_verdicts, with the share of bad registrations flagged and of good ones
/// flagged; nothing when no row has a verdict (files of older formats).
void verdict_tables(std::ostream& out, const std::vector<EvalRow>& rows);

}  // namespace partreg::eval
