// The part of a scene every device shares: [scene] name/device/duration/seed, [loop] tick, plant
// sub-steps, latency, integrator, [output] recording. Its field table is the first table of docs/scenes.md.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "sim/plants/plant_timing.hpp"
#include "tools/scene/scene_doc.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

struct LoopConfig {
  std::string name{"unnamed"};       // [scene] name
  std::string device;                // [scene] device
  double duration_s{10.0};           // [scene] duration_s
  std::uint64_t seed{1};             // [scene] seed: every random stream of the run derives from it
  double tick_us{1000.0};            // [loop] tick_us, as written
  std::int64_t tick_ns{1'000'000};   // [loop] tick_us × 1000: the controller's base tick
  int substeps{1};                   // [loop] plant_substeps per tick
  int latency_ticks{1};              // [loop] latency_ticks: command from sensor frame k applied at tick k + latency
  std::string integrator;            // [loop] integrator (device default if empty)
  int record_every{10};              // [output] record_every: CSV row every N ticks
  bool plots{true};                  // [output] plots: PNG via /usr/bin/python3 + matplotlib
  std::vector<std::string> signals;  // [output] signals: the CSV columns to record; empty = all the device's
  std::uint64_t scene_hash{0};       // the scene file's identity (tools/scene/scene_hash.hpp), not a key

  std::int64_t ticks() const;
  double tick_s() const { return 1e-9 * static_cast<double>(tick_ns); }
  plants::PlantTiming plant_timing() const { return {tick_ns, substeps, seed}; }
};

inline constexpr int kMaxLatencyTicks = 16;

// Reads the common keys; `integrators` are the device's (the first is not the default: `default_integrator`).
LoopConfig read_loop_config(SceneReader& r, const char* default_integrator,
                            std::initializer_list<std::string_view> integrators);

// The common keys for docs/scenes.md.
SceneDocTable loop_config_doc();

}  // namespace gyrostab::tools
