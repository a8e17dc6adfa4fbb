#pragma once
// The tables of tables.md about the object's parts (internal to partreg_eval): each part's error, each part
// against the same part of the truth, the seams between parts and the mesh's stretch.

#include <sstream>
#include <vector>

#include "partreg/eval/protocol.hpp"

namespace partreg::eval::detail {

/// Eq. 5 of each part, per category and variant (a table only where rows carry per-part figures).
void part_tables(std::ostringstream& out, const std::vector<EvalRow>& rows);
/// Each part against the same part of the truth, where the truth has its own parts.
void own_part_tables(std::ostringstream& out, const std::vector<EvalRow>& rows);
/// The seam gap of the part variants on clean observations.
void seam_tables(std::ostringstream& out, const std::vector<EvalRow>& rows);
/// How far the registrations stretched the canonical mesh.
void stretch_tables(std::ostringstream& out, const std::vector<EvalRow>& rows);

}  // namespace partreg::eval::detail
