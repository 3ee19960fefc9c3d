#include "sim/dynamics/eigenvalues.hpp"

#include <Eigen/Eigenvalues>

namespace gyrostab::dynamics {

Eigen::VectorXcd eigenvalues(const Eigen::MatrixXd& a) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(a, false);
  return es.eigenvalues();
}

EigenDecomposition eigen_decomposition(const Eigen::MatrixXd& a) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(a, true);
  return {es.eigenvalues(), es.eigenvectors()};
}

}  // namespace gyrostab::dynamics
