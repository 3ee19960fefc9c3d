// The gyrocompass controller (firmware/app/gyrocompass_controller.hpp) as a Cortex-M7 image (controller_image.hpp).
#include "firmware/app/gyrocompass_controller.hpp"
#include "firmware/target/controller_image.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicGyrocompassController<gyrostab::firmware::cortex_m4::DwtCycleClock>;
  gyrostab::firmware::target::run_controller_image<Controller>(Controller::Config{});
}
