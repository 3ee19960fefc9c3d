// Zero heap allocations after construction for every model × integrator over ≥ 1e6 plant steps:
// global operator new and malloc are counted (tests/support/alloc_counter.hpp), and Eigen's own
// EIGEN_RUNTIME_NO_MALLOC check is armed (eigen_assert is redefined so that it reports even with NDEBUG).
#include <atomic>
#include <cstdio>

#include "tests/support/eigen_malloc_guard.hpp"  // first: before any Eigen header

#include <gtest/gtest.h>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/model_matrix.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_start = 0;
void arm() {
  Eigen::internal::set_is_malloc_allowed(false);
  g_start = testing::allocations_so_far();
}

TEST(ZeroAllocation, EveryModelAndIntegratorAfterConstruction) {
  std::printf("malloc counted: %s\n", testing::malloc_is_counted() ? "yes" : "no (sanitizer build: operator new only)");
  for (const auto& c : testing::all_cases()) {
    const int eigen_before = g_eigen_malloc_violations.load();
    // 1e6 plant steps: ticks × sub-steps (the RK4 gimbal case takes 13 sub-steps per tick).
    const long ticks = std::string(c.name) == "gimbal_gyro/rk4" ? 80'000 : (std::string(c.name) == "lagrange_top/rk4" ? 200'000 : 1'000'000);
    const auto bytes = c.run(ticks, arm);
    const std::uint64_t allocs = testing::allocations_so_far() - g_start;
    Eigen::internal::set_is_malloc_allowed(true);
    EXPECT_EQ(allocs, 1u) << c.name << ": only the result buffer may be allocated, after the loop";
    EXPECT_EQ(g_eigen_malloc_violations.load() - eigen_before, 0) << c.name;
  }
}

}  // namespace
}  // namespace gyrostab
