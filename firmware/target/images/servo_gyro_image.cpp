// The servo gyro controller (firmware/app/servo_gyro_controller.hpp) as a Cortex-M7 image (controller_image.hpp).
#include "firmware/app/servo_gyro_controller.hpp"
#include "firmware/target/controller_image.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicServoGyroController<gyrostab::firmware::cortex_m4::DwtCycleClock>;
  gyrostab::firmware::target::run_controller_image<Controller>(Controller::Config{});
}
