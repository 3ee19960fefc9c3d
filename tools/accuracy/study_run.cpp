#include "tools/accuracy/study_run.hpp"

#include <algorithm>
#include <cstdio>

namespace gyrostab::tools::accuracy {

std::string RunSpec::setting() const {
  char buf[64];
  if (adaptive()) {
    std::snprintf(buf, sizeof buf, "tol %.0e", tolerance);
  } else {
    std::snprintf(buf, sizeof buf, "h = tick/%d", substeps);
  }
  return buf;
}

double RunResult::median(std::vector<double> w) {
  if (w.empty()) return NAN;
  std::sort(w.begin(), w.end());
  const std::size_t n = w.size();
  return n % 2 == 1 ? w[n / 2] : 0.5 * (w[n / 2 - 1] + w[n / 2]);
}

}  // namespace gyrostab::tools::accuracy
