// The position-gyro platform controller (firmware/app/position_gyro_platform_controller.hpp) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/position_gyro_platform_controller.hpp"
#include "firmware/target/pil_session.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicPositionGyroPlatformController<gyrostab::firmware::target::InstructionClock>;
  gyrostab::firmware::target::run_pil_image<Controller>("position_gyro_platform");
}
