#include "tools/accuracy/work_precision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace gyrostab::tools::accuracy {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double run_time(const StudyResult& s, const RunResult& r, int repeat) {
  const double cpu = repeat < 0 || static_cast<std::size_t>(repeat) >= r.cpu_s.size()
                         ? r.median_cpu_s()
                         : r.cpu_s[static_cast<std::size_t>(repeat)];
  return cpu / s.window_s;
}

// Each method's front for quantity q, keyed by method name, within one family.
std::map<std::string, std::vector<WorkPoint>> method_fronts(const StudyResult& s, std::size_t q, Family family,
                                                            int repeat) {
  std::map<std::string, std::vector<WorkPoint>> points;
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const RunResult& r = s.runs[i];
    if (r.spec.family != family || !r.usable(q)) continue;
    points[r.spec.method].push_back({run_time(s, r, repeat), r.comparison_error[q], i});
  }
  for (auto& [name, p] : points) p = work_front(std::move(p));
  return points;
}

struct Best {
  double time{kNaN};
  std::string method;
};

Best best_at(const std::map<std::string, std::vector<WorkPoint>>& fronts, double error) {
  Best b;
  for (const auto& [name, front] : fronts) {
    const double t = time_for_error(front, error);
    if (std::isfinite(t) && !(t >= b.time)) {
      b.time = t;
      b.method = name;
    }
  }
  return b;
}

}  // namespace

std::vector<WorkPoint> work_front(std::vector<WorkPoint> points) {
  std::sort(points.begin(), points.end(), [](const WorkPoint& a, const WorkPoint& b) {
    return a.time < b.time || (a.time == b.time && a.error < b.error);
  });
  std::vector<WorkPoint> front;
  for (const WorkPoint& p : points) {
    if (!(p.time > 0.0) || !(p.error > 0.0) || !std::isfinite(p.error)) continue;
    if (front.empty() || p.error < front.back().error) front.push_back(p);
  }
  return front;
}

double time_for_error(const std::vector<WorkPoint>& front, double error) {
  if (front.empty() || !(error > 0.0)) return kNaN;
  if (front.front().error <= error) return front.front().time;
  for (std::size_t i = 1; i < front.size(); ++i) {
    if (front[i].error <= error) {
      const WorkPoint& a = front[i - 1];
      const WorkPoint& b = front[i];
      const double u = (std::log(error) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
      return std::exp(std::log(a.time) + u * (std::log(b.time) - std::log(a.time)));
    }
  }
  return kNaN;  // more accurate than any run of the method
}

SpeedUp speed_up_at(const StudyResult& s, std::size_t q, double error, int repeat) {
  SpeedUp out;
  out.error = error;
  const Best ours = best_at(method_fronts(s, q, Family::kOurs, repeat), error);
  const auto peer_fronts = method_fronts(s, q, Family::kPeer, repeat);
  const Best peer = best_at(peer_fronts, error);
  out.peer_best_error = kNaN;
  out.peer_best_time = kNaN;
  for (const auto& [name, front] : peer_fronts) {
    if (front.empty()) continue;
    const WorkPoint& p = front.back();  // the method's most accurate point
    if (!(p.error >= out.peer_best_error)) {
      out.peer_best_error = p.error;
      out.peer_best_time = p.time;
      out.peer_best_method = name;
    }
  }
  out.ours_time = ours.time;
  out.peer_time = peer.time;
  out.ours_method = ours.method;
  out.peer_method = peer.method;
  out.ratio = std::isfinite(ours.time) && std::isfinite(peer.time) ? peer.time / ours.time : kNaN;
  out.ratio_at_least = std::isfinite(ours.time) && !std::isfinite(peer.time) && std::isfinite(out.peer_best_time)
                           ? out.peer_best_time / ours.time
                           : kNaN;
  return out;
}

std::vector<double> comparison_levels(const StudyResult& s, std::size_t q) {
  double ours_min = INFINITY, peer_min = INFINITY, most = 0.0;
  for (const RunResult& r : s.runs) {
    if (!r.usable(q)) continue;
    double& m = r.spec.family == Family::kOurs ? ours_min : peer_min;
    m = std::min(m, r.comparison_error[q]);
    most = std::max(most, r.comparison_error[q]);
  }
  std::vector<double> levels;
  const double lo = std::max(ours_min, peer_min);
  if (!std::isfinite(lo) || !(most > 0.0)) return levels;
  for (int k = static_cast<int>(std::ceil(std::log10(lo))); k <= static_cast<int>(std::floor(std::log10(most))); ++k) {
    levels.push_back(std::pow(10.0, k));
  }
  return levels;
}

std::vector<int> error_time_ranks(const StudyResult& s, std::size_t q) {
  std::vector<std::pair<double, std::size_t>> score;
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const RunResult& r = s.runs[i];
    if (r.usable(q)) score.emplace_back(r.comparison_error[q] * r.median_cpu_s(), i);
  }
  std::sort(score.begin(), score.end());
  std::vector<int> rank(s.runs.size(), 0);
  for (std::size_t k = 0; k < score.size(); ++k) rank[score[k].second] = static_cast<int>(k + 1);
  return rank;
}

}  // namespace gyrostab::tools::accuracy
