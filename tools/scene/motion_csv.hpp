// The motion record's CSV format: reading (every problem with its line) and writing.
//
//   # comment lines and blank lines are skipped anywhere
//   t [s], q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]
//   0, 1, 0, 0, 0, 0.01, 0, 0, 0, 0, 9.80665
//
// Header: comma-separated columns, each `name` or `name [unit]`, any order, each once. Required: t [s];
// the attitude q_WB, either q0 q1 q2 q3 (scalar first, unit `-` or none) or roll pitch yaw [deg|rad]
// (R_WB = Rz(yaw) Ry(pitch) Rx(roll)); the base's absolute angular velocity in base axes wx wy wz
// [rad/s|deg/s]; the specific force in base axes fx fy fz [m/s^2|m/s²|g]. Rows: one finite decimal number
// per column, within its range (|t| ≤ 1e7 s, angles ≤ 1e6 rad, |ω_i| ≤ 100 rad/s, |f_i| ≤ 1000 m/s²). Checks:
// times strictly increasing and at least 1 µs apart, no gap over `max_gap_s`, |‖q‖ − 1| ≤
// `quaternion_tolerance`, at least 3 rows. `check` and `run` read a record through this one function. Docs: docs/models/suspension-motion.md#recorded-motion.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "sim/motion/recorded_motion.hpp"

namespace gyrostab::tools {

struct MotionCsvLimits {
  double max_gap_s{0.1};                 // the longest interval between two rows [s]
  double quaternion_tolerance{1e-6};     // |‖q‖ − 1| allowed before q is normalized
  double g{motion::kStandardGravity};    // what a column in [g] is multiplied by [m/s²]
};

// Parses `text` (named `name` in messages, "name:line: ...") into `out` (finish() done). false with every
// problem found in `problems` (at most 20 of them, then a count).
bool parse_motion_csv(std::string_view text, const std::string& name, const MotionCsvLimits& limits,
                      motion::MotionRecord& out, std::vector<std::string>& problems);

// The header gyrostab writes (quaternion, SI units) and one row in it, every number in round-trip precision.
std::string motion_csv_header();
void write_motion_csv_row(std::FILE* f, double t, const dynamics::Quat& q_WB, const dynamics::Vec3& w_B,
                          const dynamics::Vec3& f_B);

}  // namespace gyrostab::tools
