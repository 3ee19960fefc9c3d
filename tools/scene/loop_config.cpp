#include "tools/scene/loop_config.hpp"

#include <cmath>

namespace gyrostab::tools {

std::int64_t LoopConfig::ticks() const {
  return static_cast<std::int64_t>(std::llround(duration_s * 1e9 / static_cast<double>(tick_ns)));
}

LoopConfig read_loop_config(SceneReader& r, const char* default_integrator,
                            std::initializer_list<std::string_view> integrators) {
  LoopConfig c;
  c.name = r.text("scene", "name", "unnamed", "scene name used in the report");
  c.device = r.text("scene", "device", "", "device model");
  c.duration_s = r.number("scene", "duration_s", 10.0, Range::closed(1e-3, 1e6), "simulated time [s]");
  c.seed = static_cast<std::uint64_t>(r.integer("scene", "seed", 1, 0, INT64_MAX, "random seed"));
  const double tick_us = r.number("loop", "tick_us", 1000.0, Range::closed(1.0, 1e6), "controller base tick [us]");
  c.tick_ns = std::llround(tick_us * 1e3);
  if (std::abs(tick_us * 1e3 - static_cast<double>(c.tick_ns)) > 1e-6) {
    r.fail("loop", "tick_us", "must be a whole number of nanoseconds");
  }
  c.substeps = static_cast<int>(r.integer("loop", "plant_substeps", 1, 1, 100000, "plant steps per tick"));
  c.latency_ticks = static_cast<int>(
      r.integer("loop", "latency_ticks", 1, 0, kMaxLatencyTicks, "ticks from sensor frame to applied command"));
  c.integrator = r.choice("loop", "integrator", default_integrator, integrators, "plant integrator");
  c.record_every = static_cast<int>(r.integer("output", "record_every", 10, 1, 1'000'000, "CSV row every N ticks"));
  c.plots = r.flag("output", "plots", true, "write PNG plots");
  c.signals = r.strings("output", "signals", "CSV columns to record; default: all of the device's");
  return c;
}

}  // namespace gyrostab::tools
