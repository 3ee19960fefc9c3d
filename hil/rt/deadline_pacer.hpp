// Real-time pacing on CLOCK_MONOTONIC absolute deadlines (the "real time" mode of the loop,
// docs/architecture.md): tick k starts at
// epoch + k · period. wait_until() sleeps with clock_nanosleep(TIMER_ABSTIME) — an absolute deadline, so a
// late tick does not shift the ones after it (no drift) — until `spin_ns` before the deadline, then spins on
// clock_gettime for the tail (the sleep's wake-up latency on a loaded kernel is tens of µs to ms; the spin
// trades a core for a sharper start). Returns the lateness of the start (now − deadline, ≥ 0 when late).
// No heap, no locks.
#pragma once

#include <time.h>

#include <cerrno>
#include <cstdint>

#include "hil/link/frame_transport.hpp"

namespace gyrostab::hil {

inline std::int64_t sleep_until(std::int64_t deadline_ns, std::int64_t spin_ns) {
  const std::int64_t wake = deadline_ns - (spin_ns > 0 ? spin_ns : 0);
  if (monotonic_ns() < wake) {
    const timespec ts = to_timespec(wake);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  std::int64_t now = monotonic_ns();
  while (now < deadline_ns && spin_ns > 0) now = monotonic_ns();
  return now - deadline_ns;
}

// Busy-waits for `ns` (a compute overrun, for the --jitter fault injection).
inline void spin_for(std::int64_t ns) {
  const std::int64_t until = monotonic_ns() + ns;
  while (monotonic_ns() < until) {
  }
}

}  // namespace gyrostab::hil
