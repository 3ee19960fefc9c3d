// The eigenvalues of a small real matrix (Eigen's EigenSolver, real Schur form), for the start-up checks that
// linearise a plant: step validation against the fastest mode, the stability of a loop's characteristic
// polynomial. Compiled once per size N, each in its own translation unit (sim/CMakeLists.txt's list, from
// sim/dynamics/eigenvalues.cpp.in): EigenSolver is among the most expensive templates to compile, and every
// scene schema needs it. Not for the hot path (not allocation-free by contract).
#pragma once

#include <Eigen/Core>
#include <complex>

namespace gyrostab::dynamics {

template <int N>
using EigenvaluesOf = Eigen::Matrix<std::complex<double>, N, 1>;

template <int N>
EigenvaluesOf<N> eigenvalues(const Eigen::Matrix<double, N, N>& a);

#define GYROSTAB_EIGENVALUES(N) \
  extern template EigenvaluesOf<N> eigenvalues<N>(const Eigen::Matrix<double, N, N>& a);
GYROSTAB_EIGENVALUES(2)
GYROSTAB_EIGENVALUES(3)
GYROSTAB_EIGENVALUES(4)
GYROSTAB_EIGENVALUES(5)
GYROSTAB_EIGENVALUES(6)
GYROSTAB_EIGENVALUES(7)
GYROSTAB_EIGENVALUES(8)
GYROSTAB_EIGENVALUES(9)
GYROSTAB_EIGENVALUES(12)
#undef GYROSTAB_EIGENVALUES

}  // namespace gyrostab::dynamics
