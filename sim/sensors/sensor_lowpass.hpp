// The bandwidth of a sensor: a unity-DC-gain low-pass of first or second order, discretized exactly for its
// sample period T (zero-order-hold equivalent: the input is constant over each sample interval).
//
//   first order   H(s) = ω₀/(s + ω₀),                ω₀ = 2π f_bw:  y_k = a y_{k−1} + (1 − a) u_k,  a =
//   e^{−ω₀T} second order  H(s) = ωn²/(s² + 2ζωn s + ωn²),   ẋ = A x + B u,  x = (y, ẏ),  A = [0 1; −ωn²
//   −2ζωn],  B = (0, ωn²)
//                 x_k = Φ x_{k−1} + Γ u_k,  Φ = e^{AT},  Γ = A⁻¹(Φ − I) B     (Franklin, Powell & Workman,
//                 Digital Control of Dynamic Systems, §4.3: the ZOH equivalent)
//                 e^{AT} = e^{μT}[C I + S (A − μI)], μ = −ζωn, ν² = ωn²(ζ² − 1): C = cosh νT, S = sinh(νT)/ν
//                 (cos, sin for ν² < 0; Taylor series when |ν²T²| < 1e-4 so ζ ≈ 1 loses no digits).
//                 ωn is set so the −3 dB frequency is f_bw for any ζ:
//                 ω_bw/ωn = √(1 − 2ζ² + √((1 − 2ζ²)² + 1))   (= 1 at ζ = 1/√2, Butterworth).
//                 Magnus's P-gyro (15.2) B β'' + d2 β' + c2 β = H Ω1 is this filter with ωn = √(c2/B),
//                 ζ = d2/(2√(B c2)); practical natural frequencies 10-60 Hz (Magnus §15.2).
//   update(u_k) takes the input sampled now (held over the interval just ended) and returns y_k: no extra
//   delay (latency is the scene's). DC gain is 1 (−C A⁻¹ B = 1 is preserved by the ZOH equivalent); the gain
//   at f_bw is 1/√2 up to the O((ω T)²) difference between the discrete and continuous responses (at f_bw =
//   fs/20: +0.036 dB first order, −0.035 dB second order; 100× less at fs/200); frequency_response() gives
//   the exact discrete one. A step held from sample 1 on reproduces the continuous step response at every
//   sample.
//
// State: y [input unit], ẏ [input unit/s] (second order). Parameters: order, f_bw [Hz] > 0, ζ [-] > 0, T [s]
// > 0. Hot path: update() is 1 (first order) or 4 multiply-adds, allocation-free. Test:
// tests/unit/sensors_test.cpp.
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include <cmath>
#include <complex>
#include <numbers>

namespace gyrostab::sensors {

struct LowpassParams {
  enum class Order { kNone, kFirst, kSecond };
  Order order{Order::kNone};
  double bandwidth_hz{100.0};               // −3 dB frequency [Hz]
  double damping{std::numbers::sqrt2 / 2};  // ζ [-], second order only
};

class SensorLowpass {
 public:
  using Order = LowpassParams::Order;

  SensorLowpass(const LowpassParams& p, double sample_period) : order_(p.order), T_(sample_period) {
    const double wb = 2.0 * std::numbers::pi * p.bandwidth_hz;
    if (order_ == Order::kFirst) {
      f11_ = std::exp(-wb * T_);
      g1_ = 1.0 - f11_;
    } else if (order_ == Order::kSecond) {
      const double z = p.damping, k = 1.0 - 2.0 * z * z;
      wn_ = wb / std::sqrt(k + std::sqrt(k * k + 1.0));
      const double mu = -z * wn_, nu2 = wn_ * wn_ * (z * z - 1.0), x = nu2 * T_ * T_;
      double c = 0.0, s = 0.0;  // C and S of the header
      if (std::abs(x) < 1e-4) {
        c = 1.0 + x / 2.0 * (1.0 + x / 12.0 * (1.0 + x / 30.0 * (1.0 + x / 56.0)));
        s = T_ * (1.0 + x / 6.0 * (1.0 + x / 20.0 * (1.0 + x / 42.0 * (1.0 + x / 72.0))));
      } else if (nu2 > 0.0) {
        const double nu = std::sqrt(nu2);
        c = std::cosh(nu * T_);
        s = std::sinh(nu * T_) / nu;
      } else {
        const double nu = std::sqrt(-nu2);
        c = std::cos(nu * T_);
        s = std::sin(nu * T_) / nu;
      }
      const double e = std::exp(mu * T_);
      const double a21 = -wn_ * wn_, a22 = -2.0 * z * wn_;
      // Φ = e^{μT}[C I + S (A − μI)]
      f11_ = e * (c - s * mu);
      f12_ = e * s;
      f21_ = e * s * a21;
      f22_ = e * (c + s * (a22 - mu));
      // Γ = A⁻¹ (Φ − I) B with A⁻¹ = [a22 −1; −a21 0]/(−a21), B = (0, −a21):
      //   (Φ − I) B = −a21 (f12, f22 − 1);  Γ = (a22 f12 − (f22 − 1), −a21 f12)
      g1_ = a22 * f12_ - (f22_ - 1.0);
      g2_ = -a21 * f12_;
    }
  }

  // Steady state at output y.
  void reset(double y) {
    y_ = y;
    dy_ = 0.0;
  }

  // One sample: u held over the interval just ended; returns the output now.
  double update(double u) {
    switch (order_) {
      case Order::kNone:
        y_ = u;
        break;
      case Order::kFirst:
        y_ = f11_ * y_ + g1_ * u;
        break;
      case Order::kSecond: {
        const double y = f11_ * y_ + f12_ * dy_ + g1_ * u;
        dy_ = f21_ * y_ + f22_ * dy_ + g2_ * u;
        y_ = y;
        break;
      }
    }
    return y_;
  }

  double output() const { return y_; }
  double natural_frequency() const { return wn_; }  // ωn [rad/s], second order
  double sample_period() const { return T_; }

  // Exact discrete response Y/U at ω [rad/s]: H(z) = C (I − Φ z⁻¹)⁻¹ Γ, z = e^{iωT}.
  std::complex<double> frequency_response(double w) const {
    const std::complex<double> zi = std::polar(1.0, -w * T_);  // z⁻¹
    switch (order_) {
      case Order::kNone:
        return 1.0;
      case Order::kFirst:
        return g1_ / (1.0 - f11_ * zi);
      case Order::kSecond: {
        // M = I − Φ z⁻¹; first row of M⁻¹ times Γ.
        const std::complex<double> m11 = 1.0 - f11_ * zi, m12 = -f12_ * zi, m21 = -f21_ * zi,
                                   m22 = 1.0 - f22_ * zi;
        return (m22 * g1_ - m12 * g2_) / (m11 * m22 - m12 * m21);
      }
    }
    return 1.0;
  }

 private:
  Order order_;
  double T_;
  double wn_{0.0};
  double f11_{1.0}, f12_{0.0}, f21_{0.0}, f22_{1.0};
  double g1_{0.0}, g2_{0.0};
  double y_{0.0}, dy_{0.0};
};

}  // namespace gyrostab::sensors
