// Alignment loops of a local-level inertial platform (levelling, then gyrocompassing), from its two level
// accelerometers to the torquers of its east, north and zenith gyros.
//
// Book: Magnus §16.5, (16.52), Fig. 16.13 (the "compass-type" loop) (docs/models/platform-alignment.md).
// Inputs: the apparent tilts θ̂_E = a_N/g0 (about the east axis) and θ̂_N = −a_E/g0 (about the north axis) [rad].
// Outputs: commanded platform rates ω_c [rad/s] of the east, north and zenith gyros.
// Levelling (both phases; second-order loops, natural frequency ω_L, damping ζ: K1 = 2ζω_L, K2 = ω_L²):
//   north gyro ← east accelerometer:  ω_cN = Ω_N − K1 θ̂_N + I_N,   I_N' = −K2 θ̂_N    (Ω_N = ω^E cosφ compensated)
//   east gyro  ← north accelerometer: ω_cE =     − K1 θ̂_E + I_E,   I_E' = −K2 θ̂_E
//   closed loop on a level-holding platform (model: θ' = ω_c − ω_needed):  θ'' + K1 θ' + K2 θ = 0.
//   In steady state the east channel's integrator carries what the east gyro must be torqued at, −(the Earth
//   rate it senses) − its drift: I_E = −Ω_N sinψ − ε_E ((16.52)), I_N the north gyro's −ε_N.
// Gyrocompassing (azimuth phase; Fig. 16.13 with the steady torquing signal as the azimuth error):
//   zenith gyro:  ω_cU = Ω_U − k_a I_E        (Ω_U = ω^E sinφ compensated; in the levelling phase ω_cU = Ω_U)
//   k_a = 1/(ω^E τ_A0): the azimuth time constant is τ_A0 at the equator and grows as 1/cosφ — the signal
//   (16.52) ∝ cosφ; there is no azimuth alignment at the poles.
//   Linearised (sim/models/platform_alignment.hpp: θ_E' = ω_cE + Ω_N ψ + ε_E, ψ' = −ω_cU + Ω_U − Ω_N θ_E − ε_U):
//     s³ + K1 s² + (K2 + Ω_N²) s + k_a K2 Ω_N = 0,   slow root ≈ −k_a Ω_N = −cosφ/τ_A0 (for k_a Ω_N << ω_L)
//   Hurwitz: K1 (K2 + Ω_N²) > k_a K2 Ω_N.
// Phases: levelling until levelling_min_s, then azimuth at the end of the first window of settle_hold_s
// (consecutive windows from t = 0) over which the mean |θ̂_E| and |θ̂_N| are below settle_tilt
// (settle_tilt = 0: at levelling_min_s).
// Sampled (control period T, integrate-then-output, the command of period k applied over period k + L,
// L = latency_periods; the platform integrates the held rate): with K = (K1, K2) of the phase
//   levelling channel  z^L (z−1)² + T K1 (z−1) + T² K2 z = 0
//   azimuth loop       z^L (z−1)³ + T (K1 (z−1) + T K2 z)(z−1) + T² Ω_N (k_a K2 T z + Ω_N (z−1) z^L) = 0
//   (the Earth-rate coupling over one period to first order in Ω_N T ~ 1e-6); check() refuses gains for
//   which either has a root on or outside the unit circle (bilinear map to the w-plane built term by term,
//   then Routh–Hurwitz: no cancellation for the roots clustered at z ≈ 1).
// Commands: levelling gyros through their torquers, M = −H ω_c (the rate-integrating gyro of (16.2),
// α0' = −M^K/H) clipped at ±torque_limit_Nm; the zenith gyro through a voltage-driven torquer of scale K_Z
// [rad/s per V], u = ω_cU/K_Z clipped at ±voltage_limit_V.
// Introspection: heading_estimate() = −I_E/Ω_N, the heading error the east gyro's torquing signal measures.
// Held frame (not fresh): integrators and the phase clock hold. O(1), no heap.
// Tests: tests/oracle/platform_alignment_test.cpp.
// Docs: docs/models/platform-alignment.md#firmware-law
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "firmware/control/config_check.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct PlatformAlignmentLoopParams {
  double latitude{0.8726646259971648};  // φ the compensation and gains assume [rad] (50°)
  double earth_rate{7.292115e-5};       // ω^E [rad/s]
  double gravity_scale{9.80665};        // g0: θ̂ = a/g0 in the sensor frame [m/s²]
  double levelling_bandwidth{0.1};      // ω_L [rad/s]
  double levelling_damping{0.7};        // ζ [-]
  double azimuth_time_constant_equator{95.0};  // τ_A0 [s]: k_a = 1/(ω^E τ_A0)
  double levelling_min_s{120.0};        // azimuth phase not before [s]
  double settle_tilt_rad{0.0};          // 0: switch at levelling_min_s; else |θ̂| below this ...
  double settle_hold_s{10.0};           // ... in its mean over windows this long [s]
  double H{0.05};                       // torquer scale of the east and north gyros [N m s]
  double azimuth_torquer_scale{2e-4};   // K_Z of the zenith gyro's torquer [rad/s per V]
  double torque_limit_Nm{0.01};         // |M| ≤ this [N m]
  double voltage_limit_V{10.0};         // |u| ≤ this [V]
  int latency_periods{1};               // L: control periods from the frame to the applied command
};

struct PlatformAlignmentGains {
  double K1{0.0}, K2{0.0};        // levelling [1/s], [1/s²]
  double k_a{0.0};                // azimuth [-]
  double Omega_N{0.0}, Omega_U{0.0};  // ω^E cosφ, ω^E sinφ [rad/s]
};

inline PlatformAlignmentGains platform_alignment_gains(const PlatformAlignmentLoopParams& p) {
  const double w = p.levelling_bandwidth;
  return {2.0 * p.levelling_damping * w, w * w, 1.0 / (p.earth_rate * p.azimuth_time_constant_equator),
          p.earth_rate * math::cos(p.latitude), p.earth_rate * math::sin(p.latitude)};
}

struct PlatformAlignmentRates {
  double east{0.0}, north{0.0}, zenith{0.0};  // ω_c [rad/s]
};

struct PlatformAlignmentCommand {
  double M_east{0.0}, M_north{0.0};  // torquer torques [N m]
  double u_zenith{0.0};              // zenith torquer voltage [V]
  bool limited{false};
};

enum class AlignmentPhase : std::uint8_t { kLevelling, kAzimuth };

class PlatformAlignmentLoops {
 public:
  PlatformAlignmentLoops(const PlatformAlignmentLoopParams& p, double T)
      : p_(p), g_(platform_alignment_gains(p)), T_(T),
        min_periods_(static_cast<std::int64_t>(std::ceil(p.levelling_min_s / T - 1e-9))),
        hold_periods_(std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(p.settle_hold_s / T - 1e-9)))) {}

  // One control period with the apparent tilts θ̂_E, θ̂_N [rad]; integrate = false (a held frame) or a
  // non-finite tilt holds the integrators and the phase clock.
  PlatformAlignmentCommand step(double tilt_east, double tilt_north, bool integrate = true) {
    const bool use = integrate && std::isfinite(tilt_east) && std::isfinite(tilt_north);
    if (use) {
      I_E_ -= g_.K2 * T_ * tilt_east;
      I_N_ -= g_.K2 * T_ * tilt_north;
    }
    rates_.east = -g_.K1 * tilt_east + I_E_;
    rates_.north = g_.Omega_N - g_.K1 * tilt_north + I_N_;
    rates_.zenith = g_.Omega_U - (phase_ == AlignmentPhase::kAzimuth ? g_.k_a * I_E_ : 0.0);
    if (use) advance_phase(tilt_east, tilt_north);
    return command(rates_);
  }
  void reset() {}  // keeps the integrators: they hold the Earth rate and drifts, not a transient

  AlignmentPhase phase() const { return phase_; }
  std::int64_t periods() const { return periods_; }
  const PlatformAlignmentRates& rates() const { return rates_; }
  const PlatformAlignmentGains& gains() const { return g_; }
  double integrator_east() const { return I_E_; }
  double integrator_north() const { return I_N_; }
  // −I_E/Ω_N: the heading error (16.52) reads from the east gyro's steady torquing signal [rad].
  double heading_estimate() const { return -I_E_ / g_.Omega_N; }

 private:
  // The residual is the mean apparent tilt over consecutive windows of settle_hold_s (noise and gusts
  // average out; a single sample would need a threshold above the accelerometer noise).
  void advance_phase(double te, double tn) {
    ++periods_;
    if (phase_ != AlignmentPhase::kLevelling) return;
    const double s = p_.settle_tilt_rad;
    if (s <= 0.0) {
      if (periods_ >= min_periods_) phase_ = AlignmentPhase::kAzimuth;
      return;
    }
    sum_E_ += te;
    sum_N_ += tn;
    if (++window_ < hold_periods_) return;
    const double n = static_cast<double>(window_);
    const bool settled = std::fabs(sum_E_ / n) < s && std::fabs(sum_N_ / n) < s;
    sum_E_ = sum_N_ = 0.0;
    window_ = 0;
    if (settled && periods_ >= min_periods_) phase_ = AlignmentPhase::kAzimuth;
  }
  static double clip(double v, double L, bool& limited) {
    if (v > L || v < -L) {
      limited = true;
      return v > 0.0 ? L : -L;
    }
    return v;
  }
  PlatformAlignmentCommand command(const PlatformAlignmentRates& w) const {
    PlatformAlignmentCommand c;
    c.M_east = clip(-p_.H * w.east, p_.torque_limit_Nm, c.limited);
    c.M_north = clip(-p_.H * w.north, p_.torque_limit_Nm, c.limited);
    c.u_zenith = clip(w.zenith / p_.azimuth_torquer_scale, p_.voltage_limit_V, c.limited);
    return c;
  }

  PlatformAlignmentLoopParams p_;
  PlatformAlignmentGains g_;
  double T_;
  std::int64_t min_periods_, hold_periods_;
  double I_E_{0.0}, I_N_{0.0};
  PlatformAlignmentRates rates_{};
  AlignmentPhase phase_{AlignmentPhase::kLevelling};
  std::int64_t periods_{0}, window_{0};
  double sum_E_{0.0}, sum_N_{0.0};  // apparent tilts summed over the current settle window [rad]
};

// --- the sampled loop's stability --------------------------------------------------------------------------

inline constexpr int kAlignmentMaxLatency = 16;
inline constexpr int kAlignmentPolyCapacity = kAlignmentMaxLatency + 4;  // degree ≤ L + 3

// Polynomial with coefficients c[0..degree] (c[i] of x^i), fixed storage.
struct AlignmentPoly {
  double c[kAlignmentPolyCapacity]{};
  int degree{0};
};

namespace detail {
inline AlignmentPoly constant_poly(double k) {
  AlignmentPoly p;
  p.c[0] = k;
  return p;
}
// p ← p · (a0 + a1 w)^n.
inline void times_linear(AlignmentPoly& p, double a0, double a1, int n = 1) {
  for (int r = 0; r < n; ++r) {
    for (int i = p.degree + 1; i >= 0; --i) {
      p.c[i] = (i <= p.degree ? a0 * p.c[i] : 0.0) + (i > 0 ? a1 * p.c[i - 1] : 0.0);
    }
    ++p.degree;
  }
}
// p ← p + q.
inline void add(AlignmentPoly& p, const AlignmentPoly& q) {
  for (int i = 0; i <= q.degree; ++i) p.c[i] += q.c[i];
  if (q.degree > p.degree) p.degree = q.degree;
}
}  // namespace detail

// Routh–Hurwitz: every root of p in the open left half-plane (p's degree ≥ 1, leading coefficient > 0).
// O(degree²).
inline bool hurwitz_stable(const AlignmentPoly& p) {
  const int n = p.degree;
  if (n < 1) return false;
  for (int i = 0; i <= n; ++i) {
    if (!(std::isfinite(p.c[i]) && p.c[i] > 0.0)) return false;  // necessary: all coefficients positive
  }
  // Rows of the Routh array, highest power first: r0 = c_n, c_{n−2}, …; r1 = c_{n−1}, c_{n−3}, ….
  constexpr int kW = kAlignmentPolyCapacity / 2 + 2;
  double a[kW]{}, b[kW]{};
  for (int j = 0; 2 * j <= n; ++j) a[j] = p.c[n - 2 * j];
  for (int j = 0; 2 * j + 1 <= n; ++j) b[j] = p.c[n - 1 - 2 * j];
  for (int row = 1; row <= n; ++row) {
    if (!(b[0] > 0.0)) return false;  // first column must stay positive (a zero is marginal: refused)
    double next[kW]{};
    for (int j = 0; j + 1 < kW; ++j) next[j] = a[j + 1] - a[0] * b[j + 1] / b[0];
    for (int j = 0; j < kW; ++j) {
      a[j] = b[j];
      b[j] = next[j];
    }
  }
  return true;
}

// The sampled loops' characteristic polynomials P(z) of the header, mapped by z = (1 + w)/(1 − w) (the unit
// disc onto the left half-plane) and multiplied by (1 − w)^deg: each term is built from the binomials
// directly, so that the roots clustered near z = 1 (|z − 1| ~ ω_L T ≪ 1) are not lost to cancellation in
// expanded z-coefficients. z − 1 → 2w, z → 1 + w, 1 → 1 − w.
// Levelling: z^L (z−1)² + T K1 (z−1) + T² K2 z.
inline AlignmentPoly levelling_characteristic_w(double K1, double K2, double T, int L) {
  using detail::times_linear;
  AlignmentPoly p = detail::constant_poly(4.0);  // (2w)² (1+w)^L
  times_linear(p, 0.0, 1.0, 2);
  times_linear(p, 1.0, 1.0, L);
  AlignmentPoly q = detail::constant_poly(2.0 * T * K1);  // T K1 (2w)(1−w)^{L+1}
  times_linear(q, 0.0, 1.0);
  times_linear(q, 1.0, -1.0, L + 1);
  detail::add(p, q);
  AlignmentPoly r = detail::constant_poly(T * T * K2);  // T² K2 (1+w)(1−w)^{L+1}
  times_linear(r, 1.0, 1.0);
  times_linear(r, 1.0, -1.0, L + 1);
  detail::add(p, r);
  return p;
}

// Azimuth: z^L (z−1)³ + T K1 (z−1)² + T² K2 z (z−1) + T³ Ω_N k_a K2 z + T² Ω_N² (z−1) z^L.
inline AlignmentPoly azimuth_characteristic_w(const PlatformAlignmentGains& g, double T, int L) {
  using detail::times_linear;
  AlignmentPoly p = detail::constant_poly(8.0);  // (2w)³ (1+w)^L
  times_linear(p, 0.0, 1.0, 3);
  times_linear(p, 1.0, 1.0, L);
  AlignmentPoly q = detail::constant_poly(4.0 * T * g.K1);  // T K1 (2w)² (1−w)^{L+1}
  times_linear(q, 0.0, 1.0, 2);
  times_linear(q, 1.0, -1.0, L + 1);
  detail::add(p, q);
  AlignmentPoly r = detail::constant_poly(2.0 * T * T * g.K2);  // T² K2 (1+w)(2w)(1−w)^{L+1}
  times_linear(r, 1.0, 1.0);
  times_linear(r, 0.0, 1.0);
  times_linear(r, 1.0, -1.0, L + 1);
  detail::add(p, r);
  AlignmentPoly u = detail::constant_poly(T * T * T * g.Omega_N * g.k_a * g.K2);  // … (1+w)(1−w)^{L+2}
  times_linear(u, 1.0, 1.0);
  times_linear(u, 1.0, -1.0, L + 2);
  detail::add(p, u);
  AlignmentPoly v = detail::constant_poly(2.0 * T * T * g.Omega_N * g.Omega_N);  // … (2w)(1+w)^L (1−w)²
  times_linear(v, 0.0, 1.0);
  times_linear(v, 1.0, 1.0, L);
  times_linear(v, 1.0, -1.0, 2);
  detail::add(p, v);
  return p;
}

// Start-up check for control period T [s]. O(L²).
inline ConfigCheck check_platform_alignment_loops(const PlatformAlignmentLoopParams& p, double T) {
  const auto fin = [](double v) { return std::isfinite(v); };
  if (!(fin(T) && T > 0.0)) return ConfigCheck::refused("platform alignment: control period must be > 0", T);
  if (!(fin(p.earth_rate) && p.earth_rate > 0.0 && p.earth_rate <= 1e-2)) {
    return ConfigCheck::refused("platform alignment: earth_rate must be in (0, 1e-2] rad/s", p.earth_rate, 0.0, 1e-2);
  }
  // (16.52) ∝ cosφ: no azimuth signal at the poles.
  constexpr double kMaxLatitude = 1.4835298641951802;  // 85°
  if (!(fin(p.latitude) && std::fabs(p.latitude) <= kMaxLatitude)) {
    return ConfigCheck::refused("platform alignment: |latitude| > 85 deg, no azimuth signal (16.52) near the poles",
                                p.latitude, -kMaxLatitude, kMaxLatitude);
  }
  if (!(fin(p.gravity_scale) && p.gravity_scale > 0.0)) {
    return ConfigCheck::refused("platform alignment: gravity_scale must be > 0", p.gravity_scale);
  }
  if (!(fin(p.levelling_bandwidth) && p.levelling_bandwidth > 0.0)) {
    return ConfigCheck::refused("platform alignment: levelling_bandwidth must be > 0", p.levelling_bandwidth);
  }
  if (!(fin(p.levelling_damping) && p.levelling_damping > 0.0 && p.levelling_damping <= 2.0)) {
    return ConfigCheck::refused("platform alignment: levelling_damping must be in (0, 2]", p.levelling_damping, 0.0, 2.0);
  }
  if (!(fin(p.azimuth_time_constant_equator) && p.azimuth_time_constant_equator > 0.0)) {
    return ConfigCheck::refused("platform alignment: azimuth_time_constant_equator must be > 0",
                                p.azimuth_time_constant_equator);
  }
  if (!(fin(p.levelling_min_s) && p.levelling_min_s >= 0.0 && fin(p.settle_tilt_rad) && p.settle_tilt_rad >= 0.0 &&
        fin(p.settle_hold_s) && p.settle_hold_s >= 0.0)) {
    return ConfigCheck::refused("platform alignment: levelling_min_s, settle_tilt_rad, settle_hold_s must be >= 0");
  }
  if (!(fin(p.H) && p.H > 0.0 && fin(p.azimuth_torquer_scale) && p.azimuth_torquer_scale > 0.0)) {
    return ConfigCheck::refused("platform alignment: H and azimuth_torquer_scale must be > 0");
  }
  if (!(fin(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0 && fin(p.voltage_limit_V) && p.voltage_limit_V > 0.0)) {
    return ConfigCheck::refused("platform alignment: torque_limit_Nm and voltage_limit_V must be > 0");
  }
  if (p.latency_periods < 0 || p.latency_periods > kAlignmentMaxLatency) {
    return ConfigCheck::refused("platform alignment: latency_periods must be in [0, 16]", p.latency_periods, 0.0,
                                kAlignmentMaxLatency);
  }
  const PlatformAlignmentGains g = platform_alignment_gains(p);
  // The continuous azimuth loop (Hurwitz of the cubic in the header).
  if (!(g.K1 * (g.K2 + g.Omega_N * g.Omega_N) > g.k_a * g.K2 * g.Omega_N)) {
    return ConfigCheck::refused(
        "platform alignment: azimuth loop unstable, K1 (K2 + Omega_N^2) <= k_a K2 Omega_N (raise "
        "azimuth_time_constant_equator)",
        p.azimuth_time_constant_equator, g.K2 * g.Omega_N / (p.earth_rate * g.K1 * (g.K2 + g.Omega_N * g.Omega_N)));
  }
  if (!hurwitz_stable(levelling_characteristic_w(g.K1, g.K2, T, p.latency_periods))) {
    return ConfigCheck::refused(
        "platform alignment: the sampled levelling loop is unstable at this control period and latency (lower "
        "levelling_bandwidth)",
        p.levelling_bandwidth * T);
  }
  if (!hurwitz_stable(azimuth_characteristic_w(g, T, p.latency_periods))) {
    return ConfigCheck::refused(
        "platform alignment: the sampled azimuth loop is unstable at this control period and latency",
        p.azimuth_time_constant_equator);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
