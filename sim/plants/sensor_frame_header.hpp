// The header of a plant's sensor frame (its device's typed frame) for tick k: publish and sample time on the plant's clock from the
// integer tick, sequence = tick, every signal zero until the plant's sensors fill it.
#pragma once

#include <cstdint>

namespace gyrostab::plants {

template <class SensorFrame>
void begin_sensor_frame(SensorFrame& f, std::int64_t tick, std::int64_t tick_ns) {
  f = SensorFrame{};
  f.tick = static_cast<std::uint64_t>(tick);
  f.time_ns = tick * tick_ns;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(tick);
}

}  // namespace gyrostab::plants
