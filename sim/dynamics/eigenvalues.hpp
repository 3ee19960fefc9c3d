// The eigenvalues of a small real matrix (Eigen's EigenSolver, real Schur form), for the start-up checks that
// linearise a plant: step validation against the fastest mode, the stability of a loop's characteristic
// polynomial. One solver for every size, compiled once (sim/dynamics/eigenvalues.cpp): EigenSolver is among
// the most expensive templates to compile, and every scene schema needs it. Not for the hot path (it
// allocates).
#pragma once

#include <Eigen/Core>
#include <complex>

namespace gyrostab::dynamics {

template <int N>
using EigenvaluesOf = Eigen::Matrix<std::complex<double>, N, 1>;

// The eigenvalues of the square matrix `a`.
Eigen::VectorXcd eigenvalues(const Eigen::MatrixXd& a);

template <int N>
EigenvaluesOf<N> eigenvalues(const Eigen::Matrix<double, N, N>& a) {
  return eigenvalues(Eigen::MatrixXd(a));
}

// The eigenvalues and the (right) eigenvectors, one per column, in the same order.
struct EigenDecomposition {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;
};
EigenDecomposition eigen_decomposition(const Eigen::MatrixXd& a);

}  // namespace gyrostab::dynamics
