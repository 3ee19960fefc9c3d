// One-sided wave elevation spectra S(ω) [m² s/rad] of a long-crested sea: Pierson-Moskowitz and JONSWAP, in
// the two-parameter (Hs, Tp) form of DNV-RP-C205 §3.5.5 (also ITTC/ISSC). Supplies the irregular sea that
// drives the ship roll damper (Magnus 14.2, where the book uses the regular wave moment E0 cos ωt (14.9)).
//
//   ωp = 2π/Tp,  m0 = ∫₀^∞ S dω = Hs²/16  (Hs is the spectral significant height Hm0 = 4√m0)
//   Pierson-Moskowitz:  S_PM(ω) = (5/16) Hs² ωp⁴ ω⁻⁵ exp(−(5/4)(ωp/ω)⁴)
//       closed-form energy below ω: ∫₀^ω S_PM = m0 · exp(−(5/4)(ωp/ω)⁴)      (substitute u = (5/4)(ωp/ω)⁴)
//       peak exactly at ωp (dS/dω = 0 ⇔ ω⁴ = ωp⁴).
//   JONSWAP:  S_J(ω) = C(γ) · S_PM(ω) · γ^r(ω),   r = exp(−(ω − ωp)² / (2 σ² ωp²)),
//       σ = σa = 0.07 for ω ≤ ωp, σ = σb = 0.09 for ω > ωp, γ = peak enhancement (3.3 mean JONSWAP, 1 ⇒ PM).
//       C(γ) is the exact normalization that keeps m0 = Hs²/16: C = m0 / (m0 + ∫ S_PM (γ^r − 1) dω), the
//       integral taken once at construction by composite Simpson (split at ωp, step σωp/200, over
//       ωp(1 − 10σa) .. ωp(1 + 10σb) where γ^r − 1 < 1e-21 outside; m0 then within 1e-13 of Hs²/16).
//       DNV's approximation C ≈ 1 − 0.287 ln γ is given by dnv_normalization() for comparison (within 0.25 %
//       of the exact C for 1 ≤ γ ≤ 5, 1.8 % low at γ = 7; see the test).
//   dnv_gamma(Hs, Tp): DNV-RP-C205 §3.5.5 default γ: 5 if Tp/√Hs ≤ 3.6, exp(5.75 − 1.15 Tp/√Hs) below 5,
//       else 1 (Tp in s, Hs in m).
//
// Parameters: Hs [m] > 0, Tp [s] > 0, γ [-] ≥ 1, σa, σb [-] in (0, 0.1) (check() returns a message
// otherwise). Assumptions: deep water, long-crested (no spreading), stationary sea state. Construction only:
// nothing here runs per tick. Test: tests/oracle/wave_spectrum_test.cpp (m0 by independent quadrature, peak
// at ωp, γ = 1 ≡ PM).
// Docs: docs/models/suspension-motion.md#waves
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gyrostab::motion {

struct WaveSpectrumParams {
  enum class Kind { kPiersonMoskowitz, kJonswap };
  Kind kind{Kind::kJonswap};
  double Hs{2.0};        // significant wave height Hm0 [m]
  double Tp{8.0};        // peak period [s]
  double gamma{3.3};     // JONSWAP peak enhancement factor [-]; ignored by PM
  double sigma_a{0.07};  // JONSWAP spectral width left of the peak [-]
  double sigma_b{0.09};  // JONSWAP spectral width right of the peak [-]
};

class WaveSpectrum {
 public:
  using Kind = WaveSpectrumParams::Kind;

  // nullptr if the parameters are usable, else what is wrong.
  static const char* check(const WaveSpectrumParams& p) {
    if (!(p.Hs > 0.0)) return "wave spectrum: Hs must be > 0 m";
    if (!(p.Tp > 0.0)) return "wave spectrum: Tp must be > 0 s";
    if (p.kind == Kind::kJonswap) {
      if (!(p.gamma >= 1.0)) return "wave spectrum: JONSWAP gamma must be >= 1";
      if (!(p.sigma_a > 0.0 && p.sigma_a < 0.1)) return "wave spectrum: sigma_a must be in (0, 0.1)";
      if (!(p.sigma_b > 0.0 && p.sigma_b < 0.1)) return "wave spectrum: sigma_b must be in (0, 0.1)";
    }
    return nullptr;
  }

  explicit WaveSpectrum(const WaveSpectrumParams& p = {})
      : p_(p),
        wp_(2.0 * std::numbers::pi / p.Tp),
        m0_(p.Hs * p.Hs / 16.0),
        ln_gamma_(p.kind == Kind::kJonswap ? std::log(p.gamma) : 0.0) {
    if (ln_gamma_ != 0.0) c_ = m0_ / (m0_ + enhancement_integral(0.0, window_hi()));
  }

  const WaveSpectrumParams& params() const { return p_; }
  double peak_frequency() const { return wp_; }  // ωp [rad/s]
  double m0() const { return m0_; }              // Hs²/16 [m²]
  double normalization() const { return c_; }    // C(γ) [-], 1 for PM

  // S(ω) [m² s/rad]; 0 for ω ≤ 0.
  double density(double w) const {
    const double s = pm_density(w);
    if (ln_gamma_ == 0.0 || s == 0.0) return c_ * s;
    return c_ * s * std::exp(peak_shape(w) * ln_gamma_);
  }

  // ∫_{w0}^{w1} S dω [m²] for 0 ≤ w0 ≤ w1: closed form for the PM part, Simpson for JONSWAP's enhancement.
  double integral(double w0, double w1) const {
    const double pm = m0_ * (pm_fraction_below(w1) - pm_fraction_below(w0));
    if (ln_gamma_ == 0.0) return c_ * pm;
    return c_ * (pm + enhancement_integral(w0, w1));
  }

  // DNV-RP-C205's approximate JONSWAP normalization.
  static double dnv_normalization(double gamma) { return 1.0 - 0.287 * std::log(gamma); }

  // DNV-RP-C205 default peak enhancement for a sea state (Hs [m], Tp [s]).
  static double dnv_gamma(double Hs, double Tp) {
    const double k = Tp / std::sqrt(Hs);
    if (k <= 3.6) return 5.0;
    if (k < 5.0) return std::exp(5.75 - 1.15 * k);
    return 1.0;
  }

  // Fraction of the PM energy below ω: exp(−(5/4)(ωp/ω)⁴).
  double pm_fraction_below(double w) const {
    if (!(w > 0.0)) return 0.0;
    const double x = wp_ / w, x2 = x * x;
    return std::exp(-1.25 * x2 * x2);
  }

 private:
  double pm_density(double w) const {
    if (!(w > 0.0)) return 0.0;
    const double x = wp_ / w, x2 = x * x, e = 1.25 * x2 * x2;
    if (e > 745.0) return 0.0;  // exp underflows to 0 before x⁵ can overflow
    return (5.0 / 16.0) * p_.Hs * p_.Hs / wp_ * x2 * x2 * x * std::exp(-e);
  }

  // r(ω) = exp(−(ω − ωp)² / (2σ²ωp²)).
  double peak_shape(double w) const {
    const double sigma = w <= wp_ ? p_.sigma_a : p_.sigma_b;
    const double d = (w - wp_) / (sigma * wp_);
    return std::exp(-0.5 * d * d);
  }

  double window_lo() const { return std::max(0.0, wp_ * (1.0 - 10.0 * p_.sigma_a)); }
  double window_hi() const { return wp_ * (1.0 + 10.0 * p_.sigma_b); }

  // ∫ S_PM (γ^r − 1) dω over [w0, w1] ∩ window, split at ωp (σ changes there).
  double enhancement_integral(double w0, double w1) const {
    double sum = 0.0;
    sum += simpson(std::max(w0, window_lo()), std::min(w1, wp_), p_.sigma_a * wp_ / 200.0);
    sum += simpson(std::max(w0, wp_), std::min(w1, window_hi()), p_.sigma_b * wp_ / 200.0);
    return sum;
  }

  double enhancement(double w) const { return pm_density(w) * std::expm1(peak_shape(w) * ln_gamma_); }

  double simpson(double a, double b, double h_max) const {
    if (!(b > a)) return 0.0;
    int n = 2 * static_cast<int>(std::ceil((b - a) / (2.0 * h_max)));
    n = std::max(n, 2);
    const double h = (b - a) / n;
    double s = enhancement(a) + enhancement(b);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * enhancement(a + i * h);
    return s * h / 3.0;
  }

  WaveSpectrumParams p_;
  double wp_;
  double m0_;
  double ln_gamma_;
  double c_{1.0};
};

}  // namespace gyrostab::motion
