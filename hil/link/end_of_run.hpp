// The end of a run on a live link (docs/protocol.md, "End of run"): after its last tick N-1 the plant sends a
// sensor frame for tick N with only the kEndOfRun status bit (and kSecondSource when it ends on a hijack), its
// values zero; the controller does not step on it and answers with an actuator frame for tick N carrying
// FaultBit::kEndOfRun, its monitor's bits and every command at its safe value. One construction of each, for
// the live ends and for the replay of a recorded bus, so that a replay compares the acknowledgement bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/fault_bits.hpp"
#include "firmware/msg/signal_spec.hpp"

namespace gyrostab::hil {

// `last_sent_tick`: the latest tick whose sensor frame the plant published. A run stopped while waiting for a
// command (a second source) has sent tick N's frame but not stepped N: the end frame is for N all the same, and
// its sequence must still advance past that frame's, or the controller would refuse it as a repeat of tick N
// with other contents.
inline msg::AnySensorFrame end_of_run_frame(std::int64_t tick, std::int64_t tick_ns, bool second_source,
                                            std::int64_t last_sent_tick = -1) {
  msg::AnySensorFrame end{};
  end.tick = static_cast<std::uint64_t>(tick);
  end.time_ns = tick * tick_ns;
  end.sample_time_ns = end.time_ns;
  end.sequence = static_cast<std::uint32_t>(tick > last_sent_tick ? tick : last_sent_tick + 1);
  end.status = msg::bit(msg::SensorStatusBit::kEndOfRun) |
               (second_source ? msg::bit(msg::SensorStatusBit::kSecondSource) : 0u);
  return end;
}

inline bool is_end_of_run(const msg::AnySensorFrame& f) {
  return (f.status & msg::bit(msg::SensorStatusBit::kEndOfRun)) != 0u;
}

// `last`: the controller's latest command frame (its sensor tick and sequence continue from it).
inline msg::AnyActuatorFrame end_of_run_ack(const msg::AnySensorFrame& end, const msg::AnyActuatorFrame& last,
                                            std::uint32_t monitor_status, std::int64_t tick_ns,
                                            const msg::DeviceSignals& signals) {
  msg::AnyActuatorFrame ack{};
  ack.tick = end.tick;
  ack.time_ns = static_cast<std::int64_t>(end.tick) * tick_ns;
  ack.sensor_tick = last.sensor_tick;
  ack.sequence = last.sequence + 1;
  ack.status = msg::bit(msg::FaultBit::kEndOfRun) | (monitor_status & 0xFFFFu);
  for (std::size_t i = 0; i < signals.commands.size(); ++i) ack.signal[i] = signals.commands[i].safe;
  return ack;
}

}  // namespace gyrostab::hil
