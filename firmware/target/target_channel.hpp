// The byte stream between a controller image and the plant: the board's UART (cmsdk_uart.hpp), or
// semihosting reads and writes on two host FIFOs (semihosting.hpp), the fast channel under QEMU. Which one is
// the emulator's choice, passed as the program's command line (QEMU: -semihosting-config ...,arg=IMAGE,arg=LINK
// with LINK "uart" or "fifo"). So the images need semihosting enabled, which the runner always does (it also
// ends the emulation through it); an image for a board without a debugger would fix the UART at build time.
// The frames on either are the same (firmware/link/target_frame.hpp). docs/pil.md explains the choice.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware/target/cmsdk_uart.hpp"
#include "firmware/target/semihosting.hpp"

namespace gyrostab::firmware::target {

class TargetChannel {
 public:
  enum class Kind : std::uint8_t { kUart, kSemihosting };

  // UART unless the command line names "fifo" and both FIFOs open (names relative to the emulator's
  // working directory: to_target, from_target).
  void open() {
    uart_.start();
    char cmdline[96]{};
    if (!semihosting::command_line(cmdline, sizeof cmdline)) return;
    if (!names_word(cmdline, "fifo")) return;
    rx_ = semihosting::open("to_target", 1);
    tx_ = semihosting::open("from_target", 5);
    if (rx_ >= 0 && tx_ >= 0) kind_ = Kind::kSemihosting;
  }

  Kind kind() const { return kind_; }

  std::size_t read_some(std::uint8_t* buf, std::size_t n) {
    return kind_ == Kind::kSemihosting ? semihosting::read(rx_, buf, n) : uart_.read_some(buf, n);
  }
  bool write(const std::uint8_t* buf, std::size_t n) {
    return kind_ == Kind::kSemihosting ? semihosting::write(tx_, buf, n) : uart_.write(buf, n);
  }

 private:
  static bool names_word(const char* text, const char* word) {
    for (const char* p = text; *p != '\0'; ++p) {
      if (p != text && p[-1] != ' ') continue;
      std::size_t i = 0;
      while (word[i] != '\0' && p[i] == word[i]) ++i;
      if (word[i] == '\0' && (p[i] == '\0' || p[i] == ' ')) return true;
    }
    return false;
  }

  CmsdkUart uart_{};
  Kind kind_{Kind::kUart};
  std::int32_t rx_{-1};
  std::int32_t tx_{-1};
};

}  // namespace gyrostab::firmware::target
