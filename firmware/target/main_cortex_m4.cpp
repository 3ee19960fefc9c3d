// The firmware as a Cortex-M4F program: the proof that scheduler, fault monitor and contract build and link
// for the target with no heap (tools/cross/build-firmware-arm). SysTick paces a 1 kHz tick; each tick the
// scheduler runs the control task (fault monitor on the received SensorFrame, command, safe state applied,
// ActuatorFrame published) and, every 100th tick, a telemetry task that snapshots the counters.
//
// The bus drivers are not part of the proof: a sensor-bus DMA is taken to write g_sensor_rx and raise
// g_sensor_rx_ready, a drive-bus DMA to send g_actuator_tx. The command itself is a placeholder (zero
// torque, brake released) where the device control laws (firmware/control/) go. The frames are the monorail's
// (gyrostab_signals/monorail_frames.hpp), a real device's generated frames; the PIL images run every device's.
#include <cstdint>

#include "firmware/fault/fault_monitor.hpp"
#include "firmware/scheduler/scheduler.hpp"
#include "firmware/target/cortex_m4_registers.hpp"
#include "firmware/target/dwt_cycle_clock.hpp"
#include "firmware/target/systick.hpp"
#include "gyrostab_signals/monorail_frames.hpp"

namespace m4 = gyrostab::firmware::cortex_m4;
namespace fw = gyrostab::firmware;
namespace msg = gyrostab::msg::monorail;

// Bus buffers and the counters snapshot, with external linkage so the compiler keeps every access.
extern "C" {
msg::SensorFrame g_sensor_rx{};          // written by the sensor-bus DMA
volatile bool g_sensor_rx_ready{false};  // set by the sensor-bus interrupt, cleared here
msg::ActuatorFrame g_actuator_tx{};      // read by the drive-bus DMA

struct Telemetry {
  fw::PerfCounter control{};  // control task counters
  fw::PerfCounter tick{};     // whole-tick counters
  fw::FaultCounters faults{};
  std::uint32_t status{0};  // fault monitor status bits
} g_telemetry{};
}

namespace {

constexpr std::uint32_t kCoreHz = 168'000'000;  // core clock [Hz]
constexpr std::uint32_t kTickHz = 1'000;        // controller tick rate [Hz]
constexpr std::int64_t kTickNs = 1'000'000'000 / kTickHz;

volatile std::uint32_t g_systicks{0};  // SysTick interrupts so far

class TargetController {
 public:
  // Fault monitor on the received frame, the command, the safe state, publication. Runs every tick.
  void control(std::uint64_t tick) {
    __asm__ volatile("" ::: "memory");  // the DMA may have written g_sensor_rx
    const bool arrived = g_sensor_rx_ready;
    g_sensor_rx_ready = false;
    const msg::SensorFrame* in = monitor_.check(arrived ? &g_sensor_rx : nullptr, tick);

    msg::ActuatorFrame out{};
    out.tick = tick;
    out.time_ns = static_cast<std::int64_t>(tick) * kTickNs;
    out.sequence = sequence_++;
    if (in != nullptr) {
      out.sensor_tick = in->tick;  // placeholder command: zero torque, brake released
    }
    monitor_.apply(out);
    g_actuator_tx = out;
    __asm__ volatile("" ::: "memory");  // publish before the DMA is started
  }

  // Counter snapshot for a debugger or a telemetry link. Every 100 ticks, phase 50 (off the control tick 0).
  void telemetry(std::uint64_t /*tick*/) {
    g_telemetry.control = scheduler_.counters(control_id_);
    g_telemetry.tick = scheduler_.tick_counters();
    g_telemetry.faults = monitor_.counters();
    g_telemetry.status = monitor_.status();
  }

  bool init() {
    const fw::AddResult c =
        scheduler_.add_member<&TargetController::control>("control", 1, 0, kTickNs / 2, *this);
    const fw::AddResult t =
        scheduler_.add_member<&TargetController::telemetry>("telemetry", 100, 50, 0, *this);
    control_id_ = c.id;
    return c.ok() && t.ok();
  }

  void run_tick(std::uint64_t tick) { scheduler_.run_tick(tick); }

 private:
  fw::Scheduler<4, m4::DwtCycleClock> scheduler_{m4::DwtCycleClock{kCoreHz}, kTickNs};
  fw::FaultMonitorOf<msg::SensorFrame> monitor_{};
  std::size_t control_id_{0};
  std::uint32_t sequence_{0};
};

TargetController g_controller;

}  // namespace

extern "C" void SysTick_Handler() {
  g_systicks = g_systicks + 1u;
}

extern "C" [[noreturn]] void firmware_main() {
  if (!g_controller.init()) __builtin_trap();
  m4::DwtCycleClock::start();
  m4::start_systick(kCoreHz / kTickHz);

  std::uint64_t tick = 0;
  std::uint32_t seen = g_systicks;
  for (;;) {
    while (g_systicks == seen) __asm__ volatile("wfi");
    seen = g_systicks;
    g_controller.run_tick(tick++);
  }
}
