// What a gyro pendulum run reports: the plant of sim/plants/gyro_pendulum_plant.hpp with its meters — the
// largest vertical error |z| beside the book's velocity-dependent error −Hw/(kR) (12.65); the deviation
// d = z − (−Hw/(kR)) split into its precession mode p = (ω^N d + i d')/(ω^N − ω^P) (the free Schuler swing:
// constant for a tuned instrument — unperturbability) and the nutation ripple d − p (excited at every
// manoeuvre corner, ~1e-6 rad); the period of p measured from zero crossings beside the book's
// (12.61)/(12.68) or (12.60); the tuned offset s of (12.66)/(12.59), k of (12.57), ω^N — the half-step error
// estimate (the Magnus model), the CSV columns, the figures, and the scene's plant and controller for the run
// modes. With the pivot on a Kepler orbit (Chelnokov §4), also the gap between the body's quaternion
// z = q_IB ∘ μ(t) and the harmonic oscillator z'' + ¼Ω²z = 0 it must obey (sim/oracles/schuler_tuning.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/gyro_pendulum_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/hysteresis_crossings.hpp"
#include "sim/models/gyro_pendulum_quaternion.hpp"
#include "sim/oracles/schuler_tuning.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/gyro_pendulum/gyro_pendulum_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::GyroPendulumPlant;
using Cplx = Plant::Cplx;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicGyroPendulumController<firmware::posix::MonotonicClock>;

class GyroPendulumRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::gyro_pendulum::Record;

  explicit GyroPendulumRun(const GyroPendulumScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        roots_(s.plant.gyro.H > 0.0
                   ? oracles::gyro_pendulum_roots(s.plant.gyro.A, s.plant.gyro.H, s.plant.gyro.k())
                   : oracles::GyroPendulumRoots{0.0, 0.0}),
        window_(s.loop.ticks() / 2, 1000),
        crossings_(s.period_threshold) {
    if (plant_.kepler()) start_kepler_oracle();
    observe(0.0);
    mode_start_ = std::abs(p_);
  }

  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    plant_.begin_tick(tick);
    if (plant_.magnus()) window_.before_tick(tick, plant_.magnus_state(), plant_.magnus_inputs());
    plant_.integrate(tick);
    if (plant_.magnus()) window_.after_tick(tick, plant_.magnus_state());
    plant_.end_tick(tick);
    ticks_ = tick + 1;
    observe(1e-9 * static_cast<double>(ticks_ * s_.loop.tick_ns));
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    constexpr double deg = 180.0 / std::numbers::pi;
    r.alpha_rad = plant_.z().real();
    r.beta_rad = plant_.z().imag();
    r.tilt_rad = plant_.tilt_rad();
    r.alpha_book_rad = zb_.real();
    r.beta_book_rad = zb_.imag();
    r.precession_mode_rad = std::abs(p_);
    r.speed_m_s = plant_.speed_m_s();
    r.heading_deg = plant_.heading_rad() * deg;
    r.latitude_deg = plant_.latitude_rad() * deg;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const auto& g = s_.plant.gyro;
    const double k = plant_.k_Nm_per_rad();
    nlohmann::json f{{"ticks", ticks_},
                     {"model", plant_.magnus() ? "magnus" : "rigid-body"},
                     {"step_s", s_.loop.tick_s() / s_.loop.substeps},
                     {"s_m", g.s},
                     {"s_tuned_m", s_.s_tuned},
                     {"k_Nm_per_rad", k},
                     {"vertical_error_max_rad", vertical_error_max_},
                     {"book_velocity_error_max_rad", book_error_max_},
                     {"deviation_from_book_max_rad", deviation_max_},
                     {"precession_mode_start_rad", mode_start_},
                     {"precession_mode_min_rad", mode_min_},
                     {"precession_mode_max_rad", mode_max_},
                     {"precession_mode_end_rad", std::abs(p_)},
                     {"nutation_ripple_max_rad", ripple_max_},
                     {"schuler_period_book_min", oracles::schuler_period(g.g, g.R) / 60.0},
                     {"period_crossings", crossings_.crossings()}};
    f["period_measured_min"] =
        crossings_.crossings() >= 2 ? nlohmann::json(crossings_.period() / 60.0) : nlohmann::json(nullptr);
    if (plant_.kepler()) {
      f["kepler_Omega_rad_s"] = kepler_Omega_;
      f["kepler_oscillator_gap_max"] = kepler_gap_;
      f["orbit_period_s"] = s_.plant.orbit.period();
    }
    if (g.H > 0.0) {
      f["nutation_frequency_rad_s"] = roots_.nutation;
      f["precession_rate_rad_s"] = roots_.precession;
      f["period_book_min"] = 2.0 * std::numbers::pi / std::abs(roots_.precession) / 60.0;  // (12.61), (12.68)
      f["nutation_over_precession"] = roots_.nutation / std::abs(roots_.precession);
    } else {
      const double T = oracles::pendulum_period(g.A, k);  // (12.60)
      f["period_book_min"] = std::isfinite(T) ? nlohmann::json(T / 60.0) : nlohmann::json(nullptr);
    }
    return f;
  }

  // report.json "error_estimate": 1000 ticks from the run's middle, the Magnus model with the scene's
  // integrator (the reference trihedron's samples are interpolated within the tick exactly as in the run).
  nlohmann::json error_estimate() const {
    if (!plant_.magnus()) {
      return {{"available", false},
              {"why", "not estimated for the rigid-body (Chelnokov) variant of the scene"}};
    }
    const auto apply = [](Plant::Magnus& m, const Plant::MagnusInputs& in) {
      m.reference() = in.ref;
      m.M1 = in.M1;
      m.M2 = in.M2;
    };
    const std::array<const char*, 4> names{"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
    const char* inv = "none watched: the vehicle's accelerations and the Earth's rotation act";
    const std::int64_t tick_ns = s_.loop.tick_ns;
    const int substeps = s_.loop.substeps;
    if (s_.plant.integrator == plants::GyroPendulumIntegrator::kRk4) {
      return error_estimate_json<4>(
          window_.estimate<dynamics::Rk4>(plant_.magnus_model(), apply, tick_ns, substeps, 4), names, inv);
    }
    return error_estimate_json<4>(
        window_.estimate<dynamics::GyroscopicExponential>(plant_.magnus_model(), apply, tick_ns, substeps, 2),
        names, inv);
  }

 private:
  // The book's steady error −Hw/(kR) (12.65) and the deviation's precession mode (homogeneous (12.58):
  // z = Z1 e^(iω^N t) + Z2 e^(iω^P t)) at the current tick's start, t [s].
  // Chelnokov §4: z = q_IB ∘ μ, μ = (cos ε/2, 0, 0, −sin ε/2), ε = c r t with c = (k − I3)/k (k = A, I3 = C:
  // the body's moments) and r its constant axial rate; z(0), z'(0) from the start (the z-form's initial values).
  void start_kepler_oracle() {
    namespace ch = models::chelnokov;
    const Plant::Body::State& x = plant_.body_state();
    const dynamics::Vec3 w0(x[0], x[1], x[2]);
    const Eigen::Map<const dynamics::Quat> q0(x.data() + Plant::Body::kAttitude);
    kepler_c_ = (s_.plant.gyro.A - s_.plant.gyro.C) / s_.plant.gyro.A;
    kepler_r_ = w0.z();
    kepler_z0_ = ch::from_eigen(q0);
    kepler_dz0_ = 0.5 * ch::mul(kepler_z0_, ch::pure(w0)) + ch::times_i3(kepler_z0_) * (-0.5 * kepler_c_ * kepler_r_);
    kepler_Omega_ = 2.0 * kepler_dz0_.norm();
  }
  void kepler_oracle(double t) {
    namespace ch = models::chelnokov;
    const Eigen::Map<const dynamics::Quat> q(plant_.body_state().data() + Plant::Body::kAttitude);
    const double eps = kepler_c_ * kepler_r_ * t;
    const ch::Quat4 mu(std::cos(0.5 * eps), 0.0, 0.0, -std::sin(0.5 * eps));
    ch::Quat4 z = ch::mul(ch::from_eigen(q), mu);
    // q and −q are one attitude: the branch the oscillator follows.
    ch::Quat4 oracle;
    for (int j = 0; j < 4; ++j) oracle[j] = oracles::kepler_oscillator(kepler_z0_[j], kepler_dz0_[j], kepler_Omega_, t);
    if (z.dot(oracle) < 0.0) z = -z;
    kepler_gap_ = std::max(kepler_gap_, (z - oracle).cwiseAbs().maxCoeff());
  }

  void observe(double t) {
    if (plant_.kepler()) kepler_oracle(t);
    const auto& g = s_.plant.gyro;
    const double k = plant_.k_Nm_per_rad();
    const motion::SuspensionSample& pivot = plant_.pivot();
    zb_ = oracles::velocity_error(g.H, k, g.R, {pivot.v_Z.x(), pivot.v_Z.y()});
    const Cplx d = plant_.z() - zb_;
    const Cplx dd = plant_.dz() - oracles::velocity_error(g.H, k, g.R, {pivot.a_Z.x(), pivot.a_Z.y()});
    p_ = g.H > 0.0 ? (roots_.nutation * d + Cplx(0.0, 1.0) * dd) / (roots_.nutation - roots_.precession) : d;
    vertical_error_max_ = std::max(vertical_error_max_, plant_.tilt_rad());
    book_error_max_ = std::max(book_error_max_, std::abs(zb_));
    deviation_max_ = std::max(deviation_max_, std::abs(d));
    mode_max_ = std::max(mode_max_, std::abs(p_));
    mode_min_ = std::min(mode_min_, std::abs(p_));
    ripple_max_ = std::max(ripple_max_, std::abs(d - p_));
    crossings_.add(t, p_.real());
  }

  const GyroPendulumScene& s_;
  Plant plant_;
  oracles::GyroPendulumRoots roots_;
  analysis::HalfStepWindow<Plant::Magnus, Plant::MagnusInputs> window_;
  analysis::HysteresisCrossings crossings_;
  ActuatorFrame last_{};
  Cplx zb_{0.0, 0.0}, p_{0.0, 0.0};
  double vertical_error_max_{0.0}, book_error_max_{0.0}, deviation_max_{0.0};
  double mode_start_{0.0}, mode_min_{1e300}, mode_max_{0.0}, ripple_max_{0.0};
  std::int64_t ticks_{0};
  models::chelnokov::Quat4 kepler_z0_{models::chelnokov::Quat4::Zero()}, kepler_dz0_{models::chelnokov::Quat4::Zero()};
  double kepler_c_{0.0}, kepler_r_{0.0}, kepler_Omega_{0.0}, kepler_gap_{0.0};
};

struct GyroPendulumTraits {
  using Scene = GyroPendulumScene;
  using Binding = GyroPendulumRun;
  using Controller = tools::Controller;
};

}  // namespace

std::unique_ptr<DeviceScene> make_gyro_pendulum_scene(std::unique_ptr<GyroPendulumScene> s) {
  return std::make_unique<DeviceSceneOf<GyroPendulumTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
