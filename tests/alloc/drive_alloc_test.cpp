// Zero heap allocations after construction for the gimbal drive (sim/drives/) and the drive loops
// (firmware/control/drive_loops.hpp) over ≥ 1e6 steps each: global operator new and malloc are counted
// (tests/support/alloc_counter.hpp), and Eigen's EIGEN_RUNTIME_NO_MALLOC check is armed (eigen_assert
// reports even with NDEBUG). The runs exercise every branch of the hot path: voltage clamp, current clamp,
// stick, breakaway, landing, reversal, disabled bridge, saturated and unsaturated PI. The cost per step is
// printed (measured, not asserted: docs/architecture.md, tests — compute time is a benchmark, not a unit-test
// assertion).
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "tests/support/eigen_malloc_guard.hpp"  // first: before any Eigen header

#include <gtest/gtest.h>

#include "firmware/control/drive_loops.hpp"
#include "firmware/scheduler/scheduler.hpp"
#include "sim/drives/gimbal_drive.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab {
namespace {

using Clock = std::chrono::steady_clock;

drives::GimbalDriveParams drive_params() {
  drives::GimbalDriveParams p;
  p.motor.R = 0.8;
  p.motor.L = 4e-4;
  p.motor.k_t = p.motor.k_e = 0.1;
  p.motor.J_m = 1e-4;
  p.motor.voltage_limit = 24.0;
  p.motor.current_limit = 6.0;
  p.gear.ratio = 10.0;
  p.gear.efficiency = 0.9;
  p.friction.coulomb = 0.3;
  p.friction.breakaway = 0.5;
  p.friction.viscous = 0.01;
  p.friction.stribeck_velocity = 0.05;
  p.command_timeout = 2.5e-4;
  return p;
}

// Cascade (10 kHz current, 1 kHz velocity, on the scheduler) + drive + inertia, 1e6 ticks = 100 s, with a
// speed reference switching every 0.5 s between +15, 0 and −15 rad/s (saturation, stick at rest, reversal).
TEST(ZeroAllocation, DriveAndCascadeOverAMillionTicks) {
  drives::GimbalDrive drive(drive_params());
  ASSERT_EQ(drives::GimbalDrive::check(drive_params()), nullptr);
  const double J = 0.05 + drive.reflected_inertia(), T = 1e-4;
  firmware::CurrentLoopSpec cs;
  cs.resistance = 0.8;
  cs.inductance = 4e-4;
  cs.period = T;
  firmware::VelocityLoopSpec vs;
  vs.inertia = J;
  vs.torque_constant = 10.0 * 0.1 * 0.9;
  vs.bandwidth = 50.0;
  vs.period = 10 * T;
  vs.current_limit = 5.0;
  firmware::DriveCascade<> cascade({firmware::design_velocity_pi(vs), firmware::design_current_pi(cs), 1.0});
  firmware::Scheduler<2> sched;
  ASSERT_TRUE((sched.add_member<&firmware::DriveCascade<>::velocity_task>("velocity", 10, 0, 0, cascade).ok()));
  ASSERT_TRUE((sched.add_member<&firmware::DriveCascade<>::current_task>("current", 1, 0, 0, cascade).ok()));

  double w = 0.0, theta = 0.0;
  long stuck_steps = 0;
  double read_sum = 0.0;  // what the sensors read: consumed, so the sampling is not optimised away
  const double refs[3] = {15.0, 0.0, -15.0};
  const long ticks = 1'000'000;
  Eigen::internal::set_is_malloc_allowed(false);
  const testing::AllocationCounter c;
  const auto t0 = Clock::now();
  for (long k = 0; k < ticks; ++k) {
    cascade.in.speed_reference = refs[(k / 5000) % 3];
    cascade.in.speed = w;
    cascade.in.current = drive.current();
    sched.run_tick(static_cast<std::uint64_t>(k));
    // Every 200 000 ticks the command goes missing for 3 ticks: watchdog fault, then cleared.
    if (k % 200'000 >= 3) drive.command_voltage(cascade.out.voltage, true);
    if (drive.fault() != drives::DriveFault::kNone && k % 200'000 == 10) drive.clear_fault();
    const drives::DriveOutput out = drive.step(T, w, {0.0, J});
    if (out.hold) w = 0.0;
    stuck_steps += out.hold ? 1 : 0;
    theta += T * w + 0.5 * T * T * out.torque / J;
    w += T * out.torque / J;
    const drives::DriveReadings r = drive.readings(theta);
    read_sum += r.current_A + static_cast<double>(r.encoder_count);
  }
  const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / ticks;
  Eigen::internal::set_is_malloc_allowed(true);
  std::printf("malloc counted: %s\n", testing::malloc_is_counted() ? "yes" : "no (sanitizer build: operator new only)");
  std::printf("cascade + drive + axis: %.1f ns per 10 kHz tick; %ld stuck steps\n", ns, stuck_steps);
  EXPECT_EQ(c.count(), 0u);
  EXPECT_GT(stuck_steps, 0);  // the stick branch ran
  EXPECT_TRUE(std::isfinite(read_sum));
  EXPECT_EQ(sched.counters(1).runs, static_cast<std::uint64_t>(ticks));
}

// The scene-runner sequence of gimbal_drive.hpp on a GimbalGyro with a drive on each axis (probe, step,
// hold, RK4): 1e6 plant steps at 1 kHz, voltage square waves, Coulomb friction with stick-slip.
TEST(ZeroAllocation, GimbalGyroWithTwoDrivesOverAMillionSteps) {
  drives::GimbalDriveParams p = drive_params();
  p.command_timeout = 0.0;
  drives::GimbalDrive d1(p), d2(p);
  using Gyro = models::GimbalGyro<models::FixedBase>;
  models::GimbalGyroParams gp;
  gp.AR = 0.4;
  gp.CR = 1.0;
  gp.AA = 0.1 + d1.reflected_inertia();
  gp.BJ = 0.05 + d2.reflected_inertia();
  Gyro gyro(gp);
  dynamics::Rk4<Gyro> integ(gyro);
  Gyro::State x = Gyro::make_state(0, 0, 0, 0, 20.0);
  const double h = 1e-3;
  const long steps = 1'000'000;
  Eigen::internal::set_is_malloc_allowed(false);
  const testing::AllocationCounter c;
  double drive_ns = 0.0;
  const auto t0 = Clock::now();
  for (long k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) * h;
    if (k % 1000 == 0) {
      const double u = (k / 1000) % 4 == 0 ? 6.0 : ((k / 1000) % 4 == 2 ? -6.0 : 0.0);
      d1.command_voltage(u, true);
      d2.command_voltage(-0.5 * u, (k / 1000) % 8 != 5);
    }
    const drives::AxisLoad l1 = drives::probe_axis_load(gyro, gyro.torques.M1, t, x, 2, d1.peak_torque());
    const drives::DriveOutput o1 = d1.step(h, x[2], l1);
    if (o1.hold) x[2] = 0.0;
    const drives::AxisLoad l2 = drives::probe_axis_load(gyro, gyro.torques.M2, t, x, 3, d2.peak_torque());
    const drives::DriveOutput o2 = d2.step(h, x[3], l2);
    if (o2.hold) x[3] = 0.0;
    gyro.torques.M1 = o1.torque;
    gyro.torques.M2 = o2.torque;
    integ.step(t, h, x);
  }
  const double total_ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / steps;
  // The drive step alone, on a fixed pattern of rates that visits slip, stick and landing.
  {
    drives::GimbalDrive d(p);
    d.command_voltage(3.0, true);
    double sink = 0.0;
    const auto s0 = Clock::now();
    for (long k = 0; k < steps; ++k) {
      const double v = (k % 7 == 0) ? 0.0 : 0.3 * static_cast<double>(k % 13 - 6);
      const drives::DriveOutput o = d.step(h, v, {0.1 * static_cast<double>(k % 5 - 2), 0.2});
      sink += o.torque;
    }
    drive_ns = std::chrono::duration<double, std::nano>(Clock::now() - s0).count() / steps;
    EXPECT_TRUE(std::isfinite(sink));
  }
  Eigen::internal::set_is_malloc_allowed(true);
  std::printf("gimbal gyro + 2 drives (2 probes, 2 drive steps, RK4): %.1f ns per plant step\n", total_ns);
  std::printf("GimbalDrive::step alone: %.1f ns\n", drive_ns);
  EXPECT_EQ(c.count(), 0u);
  EXPECT_EQ(g_eigen_malloc_violations.load(), 0);
  EXPECT_TRUE(x.allFinite());
}

}  // namespace
}  // namespace gyrostab
