// The byte transport under a plant ⇄ controller link: one send channel and one receive channel of whole
// messages (one datagram each). Implementations: LcmTransport (hil/lcm/lcm_transport.hpp, udpm:// or any LCM
// provider) and MemoryTransport (hil/link/memory_bus.hpp, two threads of one process: tests).
//
//   bool publish(const std::uint8_t* data, int size);          // false: the transport refused (counted)
//   RxStatus receive(std::int64_t deadline_ns, Message& out);  // waits for the next message on the receive
//                                                              // channel until CLOCK_MONOTONIC deadline_ns
// `Message` points into the transport's own preallocated buffer and stays valid until the next receive().
// Neither call allocates on the caller's thread after open (LCM's own receive thread may: see
// docs/transport.md).
#pragma once

#include <time.h>

#include <cstdint>
#include <limits>

namespace gyrostab::hil {

enum class RxStatus { kMessage, kTimeout, kInterrupted, kError };  // kInterrupted: a signal arrived

struct Message {
  const std::uint8_t* data{nullptr};
  int size{0};  // bytes received; a message longer than the transport's buffer has size = its true length
                // and data = nullptr (the codec rejects it by size)
};

// Buffer for one received message: generously above both frame sizes so that an oversize message is still
// measured and rejected by size, not truncated into something that decodes.
inline constexpr int kMaxMessageBytes = 2048;

inline constexpr std::int64_t kNoDeadline = std::numeric_limits<std::int64_t>::max();

inline std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

inline timespec to_timespec(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  return ts;
}

}  // namespace gyrostab::hil
