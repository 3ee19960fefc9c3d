// The power stabilizer controller (firmware/app/power_stabilizer_controller.hpp) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/power_stabilizer_controller.hpp"
#include "firmware/target/pil_session.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicPowerStabilizerController<gyrostab::firmware::target::InstructionClock>;
  gyrostab::firmware::target::run_pil_image<Controller>("power_stabilizer");
}
