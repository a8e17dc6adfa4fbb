#pragma once
// The grasp columns of results.csv and the grasp tables of tables.md (internal to partreg_eval).

#include <sstream>
#include <string>
#include <vector>

#include "partreg/eval/protocol.hpp"

namespace partreg::eval::detail {

/// The CSV header of the grasp columns (a leading comma, appended to the other columns' literal header).
#define PARTREG_GRASP_COLUMNS                                                                          \
  ",grasps,grasps_held,grasps_held_by_part,grasp_contact_per_diagonal,grasp_axis_angle_degrees,"     \
  "frame_error_median_degrees,frame_error_p90_degrees"
inline constexpr std::size_t kGraspColumnCount = 7;

/// The row's grasp fields, each preceded by a comma (empty fields without grasp figures).
std::string grasp_fields(const EvalRow& row);

/// Reads the grasp fields starting at `first` into `row` (nothing when they are empty).
void parse_grasp_fields(const std::vector<std::string>& fields, std::size_t first, EvalRow& row);

/// Grasps held on the true mesh per category, view kind and perturbation (clean, then every sweep level
/// together), per part, and the frame errors on synthetic categories.
void grasp_tables(std::ostringstream& out, const std::vector<EvalRow>& rows);

}  // namespace partreg::eval::detail
