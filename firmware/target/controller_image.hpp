// One device controller as a Cortex-M7 program (tools/cross/build-firmware-arm builds one image per device,
// firmware/target/images/): the real controller of firmware/app/ — fault monitor, scheduler, the device's laws
// and drive loops — stepped once per SysTick tick on the sensor frame the link delivered, its command left
// for the link to send.
//
// What is not here yet: the link. The image reads g_sensor_rx / g_sensor_rx_ready and writes g_actuator_tx,
// which a link driver (the board's UART or a faster channel to the plant) fills and drains; until it exists
// the images prove that every controller builds, links without a heap and fits the target, and give its size.
// The configuration is the device's defaults (Config{}); a configuration received from the plant at start-up
// (checked by the same Config::check() as on the host) replaces them once the link exists.
#pragma once

#include <cstdint>
#include <new>

#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"
#include "firmware/target/cortex_m4_registers.hpp"
#include "firmware/target/dwt_cycle_clock.hpp"
#include "firmware/target/systick.hpp"

// The link's buffers, with external linkage so the compiler keeps every access.
extern "C" {
extern gyrostab::msg::SensorFrame g_sensor_rx;    // written by the link driver
extern volatile bool g_sensor_rx_ready;           // set by the link driver, cleared by the loop
extern gyrostab::msg::ActuatorFrame g_actuator_tx;  // read by the link driver
extern volatile std::uint32_t g_systicks;         // SysTick interrupts so far
}

namespace gyrostab::firmware::target {

// ARMv7-M: the Cortex-M7's SysTick, SCB and DWT registers are the Cortex-M4's (cortex_m4_registers.hpp).
namespace regs = cortex_m4;

inline constexpr std::uint32_t kCoreHz = 216'000'000;  // core clock [Hz] (a Cortex-M7 at 216 MHz)

// Builds the controller in static storage (no heap) and steps it once per tick, for ever.
template <class Controller>
[[noreturn]] void run_controller_image(const typename Controller::Config& config) {
  alignas(Controller) static unsigned char storage[sizeof(Controller)];
  Controller& controller = *::new (storage) Controller(config, regs::DwtCycleClock{kCoreHz});
  regs::DwtCycleClock::start();
  const std::int64_t tick_ns = controller.tick_period_ns() > 0 ? controller.tick_period_ns() : 1'000'000;
  regs::start_systick(static_cast<std::uint32_t>(static_cast<std::int64_t>(kCoreHz) * tick_ns / 1'000'000'000));

  std::uint64_t tick = 0;
  std::uint32_t seen = g_systicks;
  for (;;) {
    while (g_systicks == seen) __asm__ volatile("wfi");
    seen = g_systicks;
    __asm__ volatile("" ::: "memory");  // the link driver may have written g_sensor_rx
    const bool arrived = g_sensor_rx_ready;
    g_sensor_rx_ready = false;
    controller.step(tick++, arrived ? &g_sensor_rx : nullptr, g_actuator_tx);
    __asm__ volatile("" ::: "memory");  // the command is complete before the driver sends it
  }
}

}  // namespace gyrostab::firmware::target
