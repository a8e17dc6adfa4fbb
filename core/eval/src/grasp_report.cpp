#include "grasp_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>

namespace partreg::eval::detail {
namespace {

// "body=3/5;handle=1/2": held / carried per part.
std::string by_part_field(const std::map<std::string, std::pair<int, int>>& parts) {
  std::ostringstream out;
  for (const auto& [name, counts] : parts)
    out << (out.tellp() > 0 ? ";" : "") << name << '=' << counts.first << '/' << counts.second;
  return out.str();
}

std::map<std::string, std::pair<int, int>> parse_by_part(const std::string& field) {
  std::map<std::string, std::pair<int, int>> parts;
  std::istringstream in(field);
  for (std::string item; std::getline(in, item, ';');) {
    const auto equals = item.find('='), slash = item.find('/');
    if (equals == std::string::npos || slash == std::string::npos || slash < equals)
      throw std::invalid_argument("grasps by part without 'part=held/count'");
    parts[item.substr(0, equals)] = {std::stoi(item.substr(equals + 1, slash - equals - 1)),
                                     std::stoi(item.substr(slash + 1))};
  }
  return parts;
}

std::string percent(int held, int count) {
  if (count == 0) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << 100.0 * held / count << "% (" << count << ")";
  return out.str();
}

std::vector<std::string> judged_variants(const std::vector<EvalRow>& rows) {
  std::vector<std::string> variants;
  for (const EvalRow& row : rows)
    if (row.grasps && std::find(variants.begin(), variants.end(), row.variant) == variants.end())
      variants.push_back(row.variant);
  return variants;
}

void header(std::ostringstream& out, const std::string& first, const std::vector<std::string>& variants) {
  out << "| " << first << " |";
  for (const std::string& v : variants) out << ' ' << v << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < variants.size(); ++i) out << "---|";
  out << "\n";
}

}  // namespace

std::string grasp_fields(const EvalRow& row) {
  if (!row.grasps) return std::string(kGraspColumnCount, ',');
  const GraspScore& g = *row.grasps;
  std::ostringstream out;
  out << std::setprecision(9) << ',' << g.count << ',' << g.held << ',' << by_part_field(g.by_part) << ','
      << g.contact_per_diagonal << ',';
  if (std::isfinite(g.axis_angle_degrees)) out << g.axis_angle_degrees;
  out << ',';
  if (g.frame_error_median_degrees) out << *g.frame_error_median_degrees;
  out << ',';
  if (g.frame_error_p90_degrees) out << *g.frame_error_p90_degrees;
  return out.str();
}

void parse_grasp_fields(const std::vector<std::string>& f, std::size_t first, EvalRow& row) {
  if (f.size() < first + kGraspColumnCount || f[first].empty()) return;
  GraspScore g;
  g.count = std::stoi(f[first]), g.held = std::stoi(f[first + 1]);
  g.by_part = parse_by_part(f[first + 2]);
  g.contact_per_diagonal = std::stod(f[first + 3]);
  g.axis_angle_degrees = f[first + 4].empty() ? std::nan("") : std::stod(f[first + 4]);
  if (!f[first + 5].empty()) g.frame_error_median_degrees = std::stod(f[first + 5]);
  if (!f[first + 6].empty()) g.frame_error_p90_degrees = std::stod(f[first + 6]);
  row.grasps = g;
}

void grasp_tables(std::ostringstream& out, const std::vector<EvalRow>& rows) {
  const std::vector<std::string> variants = judged_variants(rows);
  if (variants.empty()) return;
  std::set<std::string> categories;
  for (const EvalRow& row : rows) categories.insert(row.category);
  out << "\nGrasps held on the true mesh (gripper test, eval/gripper.hpp): % of the carried grasps (count), "
         "clean observations and all sweep levels together\n\n";
  header(out, "category, view, observations", variants);
  for (const std::string& category : categories)
    for (bool partial : {false, true})
      for (bool perturbed : {false, true}) {
        std::map<std::string, std::pair<int, int>> totals;
        for (const EvalRow& r : rows)
          if (r.grasps && r.category == category && in_views(r, partial) &&
              (r.perturbation != Perturbation::none) == perturbed)
            totals[r.variant].first += r.grasps->held, totals[r.variant].second += r.grasps->count;
        if (totals.empty()) continue;
        out << "| " << category << ", " << (partial ? "partial" : "full") << ", "
            << (perturbed ? "perturbed" : "clean") << " |";
        for (const std::string& v : variants) out << ' ' << percent(totals[v].first, totals[v].second) << " |";
        out << "\n";
      }
  // Per part, clean observations: the parts that vary most (a mug's handle) apart from the rest.
  std::map<std::string, std::map<std::string, std::pair<int, int>>> by_part;  // "category part view" -> variant
  for (const EvalRow& r : rows)
    if (r.grasps && r.perturbation == Perturbation::none)
      for (const auto& [part, counts] : r.grasps->by_part) {
        if (part.empty()) continue;
        auto& cell = by_part[r.category + ", " + part + ", " + (r.view >= 0 ? "partial" : "full")][r.variant];
        cell.first += counts.first, cell.second += counts.second;
      }
  if (!by_part.empty()) {
    out << "\nGrasps held on the true mesh by part, clean observations: % (count)\n\n";
    header(out, "category, part, view", variants);
    for (auto& [key, cells] : by_part) {
      out << "| " << key << " |";
      for (const std::string& v : variants) out << ' ' << percent(cells[v].first, cells[v].second) << " |";
      out << "\n";
    }
  }
  if (std::none_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.grasps && r.grasps->frame_error_median_degrees; }))
    return;
  out << "\nGrasp frame orientation error against the true motion of its region (synthetic categories), "
         "degrees, mean over clean observations of each row's median / 90th percentile\n\n";
  header(out, "category, view", variants);
  for (const std::string& category : categories)
    for (bool partial : {false, true}) {
      out << "| " << category << ", " << (partial ? "partial" : "full") << " |";
      for (const std::string& v : variants) {
        double median = 0.0, p90 = 0.0;
        int n = 0;
        for (const EvalRow& r : rows)
          if (r.grasps && r.grasps->frame_error_median_degrees && r.category == category && r.variant == v &&
              in_views(r, partial) && r.perturbation == Perturbation::none)
            median += *r.grasps->frame_error_median_degrees, p90 += *r.grasps->frame_error_p90_degrees, ++n;
        std::ostringstream cell;
        if (n > 0) cell << std::fixed << std::setprecision(1) << median / n << " / " << p90 / n;
        out << ' ' << (n > 0 ? cell.str() : "-") << " |";
      }
      out << "\n";
    }
}

}  // namespace partreg::eval::detail
