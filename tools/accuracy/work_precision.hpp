// Work-precision analysis: each method's error-against-run-time curve, the time it needs for a given error,
// and the speed-up of our best method over the best peer at equal error.
//
// How (stated in every report):
//   * A method's points are its runs over the step or tolerance sweep: x = run time (thread CPU time) per
//     simulated second (median over repeats, or one repeat's time for the spread), y = the error of one
//     quantity (RunResult::comparison_error: below the reference floor it is the floor when the reference is
//     at round-off, else the point is left out). Failed runs are left out, and so is a point that is slower and no more
//     accurate than another point of the same method (round-off or tolerance plateaus): what is left is
//     the method's front, time rising and error falling.
//   * T_m(e), the time method m needs for an error ≤ e: linear interpolation of log(time) against
//     log(error) between the two front points that bracket e; the front's cheapest time if its cheapest
//     point already meets e (no method runs cheaper than its cheapest setting: one step per tick for the
//     fixed-step ones); undefined if no point reaches e (no extrapolation).
//   * Best of a family (ours, peers) at e: the method with the least T_m(e). Speed-up at e:
//     T_best peer(e) / T_best ours(e).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tools/accuracy/study_result.hpp"

namespace gyrostab::tools::accuracy {

struct WorkPoint {
  double time{0.0};   // run time per simulated second [s/s]
  double error{0.0};
  std::size_t run{0}; // index into StudyResult::runs
};

// The front of a set of points: sorted by time, each strictly more accurate than every cheaper one.
std::vector<WorkPoint> work_front(std::vector<WorkPoint> points);

// T(e) on a front (see above); NaN where undefined.
double time_for_error(const std::vector<WorkPoint>& front, double error);

struct SpeedUp {
  double error{0.0};
  double ours_time{0.0}, peer_time{0.0};  // [s per simulated s]; NaN if the family cannot reach `error`
  double ratio{0.0};                      // peer_time / ours_time; NaN if either is undefined
  std::string ours_method, peer_method;   // best of each family at `error`
  // The peers' most accurate run (least error over every peer front) and its time; when no peer run reaches
  // `error` the speed-up is reported as a bound, ratio_at_least = its time / ours_time: a peer would need a
  // tighter setting than its most accurate one, which costs at least as much (the fronts' time grows with
  // accuracy over the settings tried). NaN when undefined (a peer reaches `error`, or ours does not).
  double peer_best_error{0.0}, peer_best_time{0.0};
  std::string peer_best_method;
  double ratio_at_least{0.0};
};

// The speed-up at `error` for quantity q; repeat < 0 uses the median time, else that repeat's time.
SpeedUp speed_up_at(const StudyResult& s, std::size_t q, double error, int repeat = -1);

// Error levels worth reporting for quantity q: the decades 10^k inside the range both families reach.
std::vector<double> comparison_levels(const StudyResult& s, std::size_t q);

// Rank (1 = best) of every run by error × time of quantity q (comparison error, median time); 0 if not usable.
std::vector<int> error_time_ranks(const StudyResult& s, std::size_t q);

}  // namespace gyrostab::tools::accuracy
