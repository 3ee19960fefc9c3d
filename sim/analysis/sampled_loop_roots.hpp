// The roots of a sampled-data loop: a continuous linear plant driven through a zero-order hold by a discrete
// linear law that runs at the tick and whose command takes effect `latency` later — what the closed loop
// (tools/loop/closed_loop.hpp) runs. The `_predicted` figures of the devices come from the continuous
// characteristic equations; these are the roots the sampled loop actually has (the `_predicted_sampled`
// figures and the schemas' sampled stability verdicts). Docs: docs/sampled-data.md.
//
//   plant   ẋ = A x + B u,   y = C x                      (continuous, linearised at the operating point)
//   law     x_c[k+1] = F x_c[k] + G y[k],  u[k] = H x_c[k] + D y[k]   (the firmware's step, exactly)
//   timing  y[k] = y(kT); the command u[k] is held over [kT + τ, (k+1)T + τ), τ = latency ≥ 0
// Over one tick, with τ = m T + τf (0 ≤ τf < T), the plant sees u[k−m−1] on [kT, kT + τf) and u[k−m] after:
//   x[k+1] = Φ x[k] + Γ1 u[k−m−1] + Γ0 u[k−m],   Φ = e^{AT},  Γ0 = ∫_0^{T−τf} e^{As} B ds,
//   Γ1 = e^{A(T−τf)} ∫_0^{τf} e^{As} B ds        (Γ1 = 0 for a whole number of ticks; Γ0 = Γ then)
// both from one matrix exponential of the augmented matrix [[A, B], [0, 0]] (Van Loan). The closed loop is
// w[k+1] = M w[k] with w = [x, x_c, u[k−1] … u[k−m−1]] (the delay line holds the commands in flight); its
// eigenvalues z map back to continuous equivalents s = ln(z)/T (principal branch: |Im s| ≤ π/T): decay rate
// −Re s, frequency Im s. Roots at z = 0 (a delay line that only shifts) have no continuous equivalent and
// are left out of `s`. For T → 0 the roots s tend to those of A + B D C (plus the law's own) with an error
// O(T) (tests/oracle/sampled_loop_roots_test.cpp).
// Host only: Eigen's dynamic matrices and eigensolver allocate; for schemas and reports, never the hot loop.
#pragma once

#include <array>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace gyrostab::analysis {

struct LinearPlant {
  Eigen::MatrixXd A, B, C;  // n×n, n×p, q×n
};

// The firmware's law as a discrete state-space (a memoryless law: F, G, H empty, u = D y).
struct DiscreteLaw {
  Eigen::MatrixXd F, G, H, D;  // r×r, r×q, p×r, p×q
  static DiscreteLaw gain(const Eigen::MatrixXd& D);
};

struct SampledTiming {
  double period_s{1e-3};   // T: the law's period (tick × control divisor)
  double latency_s{1e-3};  // τ: from the sample to the command's taking effect (latency_ticks × base tick)
};

struct SampledLoopRoots {
  Eigen::MatrixXd M;                       // the discrete closed loop w[k+1] = M w[k]
  std::vector<std::complex<double>> z;     // all eigenvalues of M
  std::vector<std::complex<double>> s;     // ln(z)/T of the non-zero ones [1/s]
  double max_abs_z{0.0};                   // spectral radius: < 1 iff the sampled loop is stable
  bool stable() const { return max_abs_z < 1.0; }
};

// Φ and Γ of a plant over t: {e^{At}, ∫_0^t e^{As} B ds}.
struct ZohStep {
  Eigen::MatrixXd Phi, Gamma;
};
ZohStep zoh_step(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double t);

Eigen::MatrixXd sampled_closed_loop(const LinearPlant& p, const DiscreteLaw& law, const SampledTiming& t);
SampledLoopRoots sampled_loop_roots(const LinearPlant& p, const DiscreteLaw& law, const SampledTiming& t);

// A plant ẋ = A x + B u under a state feedback u = K x, restricted to the states `keep` (those that act: a
// coordinate nothing reads and nothing feeds is a neutral root, z = 1 sampled, that says nothing about the
// loop): the plant with y = x on those states and the law u = K x as a memoryless DiscreteLaw.
struct StateFeedbackLoop {
  LinearPlant plant;
  DiscreteLaw law;
};
StateFeedbackLoop restrict_state_feedback(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& K,
                                          const std::vector<int>& keep);

// The sampled loop's fixed point under a constant plant input v (ẋ = A x + B u + E v): the plant state x*
// (with a memoryless law the continuous loop's equilibrium: ZOH keeps equilibria). NaN when I − M is singular
// (a neutral mode, e.g. the back-EMF stabilizer's α).
Eigen::VectorXd sampled_steady_state(const LinearPlant& p, const DiscreteLaw& law, const SampledTiming& t,
                                     const Eigen::MatrixXd& E, const Eigen::VectorXd& v);

// The sampled root nearest to a continuous one (the same mode moved by the sampling), returned in the
// half-plane of `continuous` (Im s ≥ 0 when Im continuous ≥ 0). Matching by distance rather than by "largest
// |Im|" keeps a delay line's fast roots (near z = 0, |Im s| up to π/T) from being taken for the mode.
std::complex<double> nearest_root(const std::vector<std::complex<double>>& s, std::complex<double> continuous);

// The two roots of s nearest `centre`, each taken once: a pair near a double root (a PI designed to one, an
// attitude loop at ζ = 1), whose members are ill-conditioned one by one.
std::array<std::complex<double>, 2> nearest_pair(std::vector<std::complex<double>> s, std::complex<double> centre);

// A real or conjugate pair as natural frequency ω_n = √(s1 s2) [rad/s] and damping ratio
// ζ = −(s1 + s2)/(2 ω_n): smooth in the loop's coefficients where the roots themselves are not.
struct PairShape {
  double natural_frequency{0.0}, damping_ratio{0.0};
};
PairShape pair_shape(std::complex<double> s1, std::complex<double> s2);

// The sampled verdict in words for a schema's message: "" when stable; else e.g. "unstable at tick 5 ms
// with latency 1 tick(s): |z| = 1.03" (prefixed by "stable in continuous time but " when continuous_stable).
std::string sampled_instability(const SampledLoopRoots& r, const SampledTiming& t, bool continuous_stable);

}  // namespace gyrostab::analysis
