// Arms Eigen's EIGEN_RUNTIME_NO_MALLOC check so that it reports even in a Release (NDEBUG) build:
// eigen_assert is redefined to count violations in g_eigen_malloc_violations instead of aborting.
// Include it FIRST in a test file, before any Eigen header (Eigen reads both macros when first included);
// then Eigen::internal::set_is_malloc_allowed(false) around the measured loop.
#pragma once

#include <atomic>

namespace {
std::atomic<int> g_eigen_malloc_violations{0};
}
#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x)                                                            \
  do {                                                                             \
    if (!(x)) g_eigen_malloc_violations.fetch_add(1, std::memory_order_relaxed);   \
  } while (false)
