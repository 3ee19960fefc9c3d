#include "tools/scene/loop_config.hpp"

#include <cmath>
#include <cstdint>

#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using F = schema::Fields<LoopConfig>;

void set_tick_us(LoopConfig& c, double us) {
  c.tick_us = us;
  c.tick_ns = std::llround(us * 1e3);
}

constexpr schema::Field<LoopConfig> kFields[] = {
    F::text("scene", "name", "scene name used in the report and the plot title", GS_TEXT(name)),
    F::number("scene", "duration_s", "s", Range::closed(1e-3, 1e6), "simulated time", GS_NUMBER(duration_s)),
    F::integer("scene", "seed", "", 0, INT64_MAX, "seed of every random stream of the run", GS_INTEGER(seed)),
    F::number("loop", "tick_us", "µs", Range::closed(1.0, 1e6),
              "the controller's base tick: a SensorFrame in, an ActuatorFrame out; a whole number of ns",
              set_tick_us, [](const LoopConfig& c) { return c.tick_us; }),
    F::integer("loop", "plant_substeps", "", 1, 100000, "plant integrator steps per base tick", GS_INTEGER(substeps)),
    F::integer("loop", "latency_ticks", "ticks", 0, kMaxLatencyTicks,
               "the command computed from the sensor frame of tick k acts from tick k + latency",
               GS_INTEGER(latency_ticks)),
    F::integer("output", "record_every", "ticks", 1, 1'000'000, "one CSV row every N ticks", GS_INTEGER(record_every)),
    F::flag("output", "plots", "write signals.png (matplotlib through /usr/bin/python3)", GS_FLAG(plots)),
    F::strings("output", "signals",
               "the CSV columns to record, in this order (a run records only these); an unknown or repeated name is "
               "refused with the list of valid ones",
               GS_STRINGS(signals)),
};

}  // namespace

std::int64_t LoopConfig::ticks() const {
  return static_cast<std::int64_t>(std::llround(duration_s * 1e9 / static_cast<double>(tick_ns)));
}

LoopConfig read_loop_config(SceneReader& r, const char* default_integrator,
                            std::initializer_list<std::string_view> integrators) {
  LoopConfig c;
  c.scene_hash = r.text_hash();
  c.device = r.text("scene", "device", "", "device model");
  schema::read(r, kFields, c);
  if (std::abs(c.tick_us * 1e3 - static_cast<double>(c.tick_ns)) > 1e-6) {
    r.fail("loop", "tick_us", "must be a whole number of nanoseconds");
  }
  c.integrator = r.choice("loop", "integrator", default_integrator, integrators, "plant integrator");
  return c;
}

SceneDocTable loop_config_doc() {
  SceneDocTable t = schema::document(kFields);
  t.rows.insert(t.rows.begin() + 1, SceneDocRow{"`[scene] device`", "device model", "–", "required",
                                                "one of the devices below"});
  t.rows.insert(t.rows.begin() + 6, SceneDocRow{"`[loop] integrator`", "plant integrator", "–", "the device's (below)",
                                                "the device's list (below)"});
  return t;
}

}  // namespace gyrostab::tools
