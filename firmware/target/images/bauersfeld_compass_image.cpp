// The bauersfeld_compass device's controller (firmware/app/free_instrument_controller.hpp on its frames) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/free_instrument_controller.hpp"
#include "firmware/target/pil_session.hpp"
#include "gyrostab_signals/bauersfeld_compass_frames.hpp"

extern "C" [[noreturn]] void firmware_main() {
  namespace firmware = gyrostab::firmware;
  namespace device = gyrostab::msg::bauersfeld_compass;
  using Controller = firmware::BasicFreeInstrumentControllerOf<device::SensorFrame, device::ActuatorFrame,
                                                              firmware::target::InstructionClock>;
  firmware::target::run_pil_image<Controller>("bauersfeld_compass");
}
