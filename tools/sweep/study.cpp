#include "tools/sweep/study.hpp"

namespace gyrostab::tools::sweep {

double Study::probability_sum() const {
  double sum = 0.0;
  for (const SeaStateCell& c : cells) sum += c.probability;
  return sum;
}

double Study::probability(int cell, int heading) const {
  const double cells_sum = probability_sum();
  double headings_sum = 0.0;
  for (double q : heading_probability) headings_sum += q;
  const double q = heading_probability.empty() ? 1.0 : heading_probability[static_cast<std::size_t>(heading)] / headings_sum;
  return cells_sum > 0.0 ? cells[static_cast<std::size_t>(cell)].probability / cells_sum * q : 0.0;
}

std::string variant_name_problem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() > 64) return "is longer than 64 characters";
  if (name.front() == '.') return "starts with '.' (it names a directory: '.', '..' and hidden names are refused)";
  for (char ch : name) {
    const bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '.' ||
                    ch == '_' || ch == '-';
    if (!ok) return "holds a character outside [A-Za-z0-9._-] (it names a directory)";
  }
  return "";
}

}  // namespace gyrostab::tools::sweep
