// What a task leaves: its outcome (completed, diverged with the guard's reason, refused with the scene
// reader's problems), the figures a sizing study compares, its timings, and the scene that ran. As JSON, one
// file per task (task_store.hpp), with two checks: the hash of the task's definition (its scene text and its
// place in the study), so a file of another study or another version of this one is stale, and a check of
// its result fields, so a damaged file is found, not used.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "tools/sweep/study.hpp"
#include "tools/sweep/task.hpp"

namespace gyrostab::tools::sweep {

inline constexpr const char* kTaskFormat = "gyrostab-sweep-task/1";

// The figures a task keeps from the ship roll damper's report.json "figures", in table order. One the build
// does not report is null, never 0 (stop_contacts and the mount loads come with the hull model's moments).
inline constexpr std::array<std::string_view, 12> kTaskFigures{
    "roll_rms_rad",      "roll_rms_unstabilized_rad", "roll_rms_ratio",         "roll_reduction",
    "roll_max_rad",      "precession_max_rad",        "precession_torque_max_Nm", "stop_contacts",
    "roll_moment_max_Nm", "yaw_moment_max_Nm",        "yaw_moment_unit_max_Nm", "pitch_moment_max_Nm"};

inline constexpr std::string_view kCompleted = "completed";
inline constexpr std::string_view kDiverged = "diverged";
inline constexpr std::string_view kRefused = "refused";

// 64-bit FNV-1a as 16 hex digits: finds a changed definition or a damaged file, not an adversary.
std::string fnv1a64_hex(std::string_view text);

// The hash of what decides a task's result: the format, its place (variant name, cell, heading, replicate)
// and its scene text. Not the probabilities: re-weighting a table reuses every task.
std::string definition_hash(const Study& s, const Task& t, const std::string& scene_text);

// The check of a record's result fields (outcome, reasons, figures).
std::string result_check(const nlohmann::json& record);

// The "task" block: where the task sits in the study.
nlohmann::json task_block(const Study& s, const Task& t);

}  // namespace gyrostab::tools::sweep
