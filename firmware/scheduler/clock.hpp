// What the scheduler needs from a time source: a callable returning monotonic time in integer nanoseconds.
// The scheduler never calls an OS: the host injects CLOCK_MONOTONIC (firmware/platform/posix/), a Cortex-M
// target its cycle counter (firmware/target/dwt_cycle_clock.hpp), tests a fake clock they advance by hand.
#pragma once

#include <concepts>
#include <cstdint>

namespace gyrostab::firmware {

// A clock is any copyable callable `c()` -> std::int64_t [ns], never decreasing. A plain function pointer
// `std::int64_t (*)()` qualifies.
template <class C>
concept MonotonicClock = std::copy_constructible<C> && requires(C& c) {
  { c() } -> std::same_as<std::int64_t>;
};

// A clock that always reads 0: compute times are all 0, runs are still counted. For deterministic
// in-process runs that must not read a wall clock.
struct NullClock {
  constexpr std::int64_t operator()() const { return 0; }
};

}  // namespace gyrostab::firmware
