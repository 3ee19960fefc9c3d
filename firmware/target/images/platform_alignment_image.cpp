// The platform alignment controller (firmware/app/platform_alignment_controller.hpp) as a Cortex-M7 processor-in-the-loop image (pil_session.hpp).
#include "firmware/app/platform_alignment_controller.hpp"
#include "firmware/target/pil_session.hpp"

extern "C" [[noreturn]] void firmware_main() {
  using Controller = gyrostab::firmware::BasicPlatformAlignmentController<gyrostab::firmware::target::InstructionClock>;
  gyrostab::firmware::target::run_pil_image<Controller>("platform_alignment");
}
