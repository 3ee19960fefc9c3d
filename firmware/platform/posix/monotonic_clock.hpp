// Host port of the scheduler's time source: CLOCK_MONOTONIC in integer nanoseconds (POSIX clock_gettime).
// The one firmware/ file that calls the OS; it is the host's platform layer, not target code, so the
// cross build (tools/cross/build-firmware-arm) leaves firmware/platform/posix/ out.
#pragma once

#include <time.h>

#include <cstdint>

namespace gyrostab::firmware::posix {

struct MonotonicClock {
  std::int64_t operator()() const {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + static_cast<std::int64_t>(ts.tv_nsec);
  }
};

}  // namespace gyrostab::firmware::posix
