// The servo gyro controller (firmware/app/servo_gyro_controller.hpp) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/servo_gyro_controller.hpp"
#include "firmware/target/pil_session.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicServoGyroController<gyrostab::firmware::target::InstructionClock>;
  gyrostab::firmware::target::run_pil_image<Controller>("servo_gyro");
}
