#pragma once
// What every table of tables.md is made of (internal to partreg_eval): means over the rows that a table's
// cell stands for, the cell's text, and a table's header.

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "partreg/eval/protocol.hpp"

namespace partreg::eval::detail {

/// Mean of `value` over the rows `keep` accepts; NaN for none.
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

/// Mean of `value` over the clean observations of one category and method, full or partial views: what
/// every table of clean figures shows in a cell.
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

/// A table cell: `value` times `factor` with `precision` decimals; "-" for no value.
inline std::string cell(double value, double factor = 1e4, int precision = 2) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << value * factor;
  return out.str();
}

/// A table's header line and its separator: `first`, then one column per name.
inline void header_row(std::ostringstream& out, const std::string& first,
                       const std::vector<std::string>& columns) {
  out << "| " << first << " |";
  for (const std::string& column : columns) out << ' ' << column << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << "\n";
}

}  // namespace partreg::eval::detail
