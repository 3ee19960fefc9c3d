// The buffers every controller image shares with its link driver (controller_image.hpp), and the SysTick
// interrupt that paces the loop.
#include <cstdint>

#include "firmware/target/controller_image.hpp"

extern "C" {
gyrostab::msg::SensorFrame g_sensor_rx{};
volatile bool g_sensor_rx_ready{false};
gyrostab::msg::ActuatorFrame g_actuator_tx{};
volatile std::uint32_t g_systicks{0};

void SysTick_Handler() { g_systicks = g_systicks + 1u; }
}
