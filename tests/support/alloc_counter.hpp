// Counts heap allocations made by this process: global operator new (every form) and, outside sanitizer
// builds (whose runtime owns malloc), malloc/calloc/realloc through glibc's __libc_* entry points.
// Use: AllocationCounter c; ...hot loop...; EXPECT_EQ(c.count(), 0).
#pragma once

#include <cstdint>

namespace gyrostab::testing {

std::uint64_t allocations_so_far();
std::uint64_t allocations_on_this_thread();  // the same count, only the calling thread's allocations
bool malloc_is_counted();  // false in sanitizer builds: only operator new is counted there

class AllocationCounter {
 public:
  AllocationCounter() : start_(allocations_so_far()) {}
  std::uint64_t count() const { return allocations_so_far() - start_; }

 private:
  std::uint64_t start_;
};

}  // namespace gyrostab::testing
