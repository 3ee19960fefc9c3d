// The ship roll damper controller (firmware/app/ship_roll_damper_controller.hpp) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/ship_roll_damper_controller.hpp"
#include "firmware/target/pil_session.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicShipRollDamperController<gyrostab::firmware::target::InstructionClock>;
  gyrostab::firmware::target::run_pil_image<Controller>("ship_roll_damper");
}
