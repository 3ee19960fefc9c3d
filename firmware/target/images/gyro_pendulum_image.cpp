// The gyro pendulum controller (firmware/app/gyro_pendulum_controller.hpp) as a Cortex-M7 image (controller_image.hpp).
#include "firmware/app/gyro_pendulum_controller.hpp"
#include "firmware/target/controller_image.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicGyroPendulumController<gyrostab::firmware::cortex_m4::DwtCycleClock>;
  gyrostab::firmware::target::run_controller_image<Controller>(Controller::Config{});
}
