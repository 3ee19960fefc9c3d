// Reduced model against the full model on the same scene, in the same invocation: the full-model plant runs
// the scene first with its compared signals traced (TracingDevice); then the reduced plant runs the same loop
// (same seed, sensors, controller and inputs) while ComparingDevice takes the largest difference of each
// compared signal from the trace, tick by tick. Both runs are deterministic, so the measured error is too.
// Nothing is allocated per tick: the trace is sized before the first loop.
//
// A compared plant provides, besides the plant concept (plant_port.hpp; its typed frames and its Record, which
// both wrappers forward):
//   static constexpr int kComparedSignals;              // ≤ kMaxComparedSignals
//   static const char* compared_signal_name(int i);
//   double compared_signal(int i) const;                 // after advance(k): the value at the end of tick k
// The trace keeps every tick up to kMaxTraceSamples samples, else every stride-th tick (the comparison is then
// made at those ticks only; the report says which stride).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tools/loop/loop_outcome.hpp"

namespace gyrostab::tools {

inline constexpr int kMaxComparedSignals = 8;
inline constexpr std::int64_t kMaxTraceSamples = 2'000'000;

struct ComparisonTrace {
  int signals{0};
  std::int64_t stride{1};
  std::int64_t samples{0};
  std::vector<double> values;  // [sample][signal]

  void size_for(std::int64_t ticks, int n) {
    signals = n;
    stride = std::max<std::int64_t>(1, (ticks + kMaxTraceSamples - 1) / kMaxTraceSamples);
    values.assign(static_cast<std::size_t>((ticks / stride + 1) * n), 0.0);
    samples = 0;
  }
  bool due(std::int64_t tick) const { return (tick + 1) % stride == 0; }
  std::int64_t index(std::int64_t tick) const { return (tick + 1) / stride - 1; }
};

// The full-model run: the device's loop, its compared signals traced after every advance.
template <class Device>
class TracingDevice {
 public:
  using SensorFrame = typename Device::SensorFrame;
  using ActuatorFrame = typename Device::ActuatorFrame;
  using Record = typename Device::Record;

  TracingDevice(Device& d, ComparisonTrace& trace) : d_(d), trace_(trace) {}
  void sense(std::int64_t k, SensorFrame& f) { d_.sense(k, f); }
  void actuate(const ActuatorFrame& c) { d_.actuate(c); }
  void advance(std::int64_t k) {
    d_.advance(k);
    if (!trace_.due(k)) return;
    const std::int64_t i = trace_.index(k);
    if (static_cast<std::size_t>((i + 1) * trace_.signals) > trace_.values.size()) return;
    for (int s = 0; s < trace_.signals; ++s) {
      trace_.values[static_cast<std::size_t>(i * trace_.signals + s)] = d_.compared_signal(s);
    }
    trace_.samples = i + 1;
  }
  bool finite() const { return d_.finite(); }
  void record(Record& row) const { d_.record(row); }
  nlohmann::json figures() const { return nlohmann::json::object(); }

 private:
  Device& d_;
  ComparisonTrace& trace_;
};

// What the comparison's report block needs from outside the reduced run.
struct ComparisonSetup {
  nlohmann::json expected;        // ε and the a-priori bounds, per compared signal "<name>_bound"
  double full_wall_s{0.0};        // the full-model loop's wall time (timing, not figures)
  std::int64_t full_ticks{0};
  bool full_diverged{false};
  std::int64_t full_diverged_tick{-1};
  int full_substeps{1};
  std::string full_integrator;
};

// The reduced-model run: owns the reduced plant (built in place from `args`), the full model's trace and the
// comparison's set-up; forwards the plant concept (and the optional guard, figures, error estimate, report
// blocks) to the reduced plant, and compares its compared signals with the trace after every traced tick.
template <class Device>
class ComparingDevice {
 public:
  static_assert(Device::kComparedSignals <= kMaxComparedSignals);
  using SensorFrame = typename Device::SensorFrame;
  using ActuatorFrame = typename Device::ActuatorFrame;
  using Record = typename Device::Record;
  static constexpr int kGuardedStates = Device::kGuardedStates;
  static const char* state_name(int i) { return Device::state_name(i); }
  double state_value(int i) const { return d_.state_value(i); }

  template <class... Args>
  ComparingDevice(std::unique_ptr<const ComparisonTrace> trace, ComparisonSetup setup, Args&&... args)
      : d_(std::forward<Args>(args)...), trace_(*trace), owned_trace_(std::move(trace)), setup_(std::move(setup)) {}

  void sense(std::int64_t k, SensorFrame& f) { d_.sense(k, f); }
  void actuate(const ActuatorFrame& c) { d_.actuate(c); }
  void advance(std::int64_t k) {
    d_.advance(k);
    if (!trace_.due(k)) return;
    const std::int64_t i = trace_.index(k);
    if (i >= trace_.samples) return;
    for (int s = 0; s < Device::kComparedSignals; ++s) {
      const double e = std::abs(d_.compared_signal(s) - trace_.values[static_cast<std::size_t>(i * trace_.signals + s)]);
      auto& worst = max_error_[static_cast<std::size_t>(s)];
      if (!(e <= worst)) worst = e;  // NaN propagates: a non-finite difference is never hidden
      sum_sq_[static_cast<std::size_t>(s)] += e * e;
    }
    ++compared_;
  }
  bool finite() const { return d_.finite(); }
  void record(Record& row) const { d_.record(row); }
  nlohmann::json figures() const { return d_.figures(); }
  nlohmann::json error_estimate() const requires requires(const Device& d) { d.error_estimate(); } {
    return d_.error_estimate();
  }

  // report.json "reduced_model": the expected error, the measured error against the full model.
  nlohmann::json report_extra() const {
    nlohmann::json out = nlohmann::json::object();
    if constexpr (requires(const Device& d) { d.report_extra(); }) out = d_.report_extra();
    nlohmann::json b = setup_.expected;
    nlohmann::json measured = nlohmann::json::object();
    bool within = compared_ > 0 && !setup_.full_diverged;
    for (int s = 0; s < Device::kComparedSignals; ++s) {
      const std::string name = Device::compared_signal_name(s);
      const double e = max_error_[static_cast<std::size_t>(s)];
      measured[name + "_max"] = std::isfinite(e) ? nlohmann::json(e) : nlohmann::json(nullptr);
      measured[name + "_rms"] = compared_ > 0 ? std::sqrt(sum_sq_[static_cast<std::size_t>(s)] / static_cast<double>(compared_))
                                              : 0.0;
      const std::string bound = name + "_bound";
      if (b.contains(bound) && b[bound].is_number()) within = within && std::isfinite(e) && e <= b[bound].get<double>();
    }
    b["measured_error"] = measured;
    b["compared_ticks"] = compared_;
    b["compared_every_ticks"] = trace_.stride;
    // A named value, not a braced list assigned in place: clang 14 then leaves the replaced string (the
    // expected block's "full_model" note) undestroyed, which its leak sanitizer reports on every run.
    nlohmann::json full_model = {{"integrator", setup_.full_integrator}, {"plant_substeps", setup_.full_substeps},
                                 {"ticks", setup_.full_ticks}, {"diverged", setup_.full_diverged}};
    b["full_model"] = std::move(full_model);
    if (setup_.full_diverged) b["full_model"]["diverged_at_tick"] = setup_.full_diverged_tick;
    b["within_bounds"] = within;
    out["reduced_model"] = b;
    return out;
  }
  // report.json timing.reduced_model: the run-time ratio (wall time varies: not a figure).
  nlohmann::json extra_timing(const LoopOutcome& reduced) const {
    return {{"reduced_model",
             {{"full_wall_s", setup_.full_wall_s},
              {"reduced_wall_s", reduced.wall_s},
              {"run_time_ratio_reduced_over_full", setup_.full_wall_s > 0 ? reduced.wall_s / setup_.full_wall_s : 0.0},
              {"speed_up_full_over_reduced", reduced.wall_s > 0 ? setup_.full_wall_s / reduced.wall_s : 0.0}}}};
  }

 private:
  Device d_;
  const ComparisonTrace& trace_;
  std::unique_ptr<const ComparisonTrace> owned_trace_;
  ComparisonSetup setup_;
  std::array<double, kMaxComparedSignals> max_error_{};
  std::array<double, kMaxComparedSignals> sum_sq_{};
  std::int64_t compared_{0};
};

}  // namespace gyrostab::tools
