// A composed plant's clock and seed, from the scene's loop: the base tick, the integrator's sub-steps per tick
// and the scene seed every random stream of the plant derives from (sim/random/seeded_rng.hpp).
#pragma once

#include <cstdint>

namespace gyrostab::plants {

// The plant's clock and seed: base tick [ns], integrator sub-steps per tick, the scene seed.
struct PlantTiming {
  std::int64_t tick_ns{1'000'000};
  int substeps{1};
  std::uint64_t seed{1};
  double tick_s() const { return 1e-9 * static_cast<double>(tick_ns); }
};

}  // namespace gyrostab::plants
