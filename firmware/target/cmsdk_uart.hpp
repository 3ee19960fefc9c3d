// The CMSDK APB UART of Arm's MPS2 boards (Arm, "Cortex-M System Design Kit Technical Reference Manual",
// 4.2; UART0 of the AN500 image at 0x40004000), polled: DATA (+0), STATE (+4: bit 0 TX buffer full, bit 1 RX
// buffer full), CTRL (+8: bit 0 TX enable, bit 1 RX enable), BAUDDIV (+0x10, at least 16). Each direction
// holds one byte.
// Polled, not interrupt-driven: in lockstep the controller has nothing else to do while it waits for the
// next frame, and a polled driver has no shared state between an interrupt and the loop to get wrong. A
// board that must keep its control tick while bytes arrive would take RX in the UART interrupt into a ring
// buffer; the frame decoder (firmware/link/target_frame.hpp) takes bytes either way.
// No heap; write() spins while the TX byte is full, read_some() while nothing has arrived.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware/target/cortex_m4_registers.hpp"

namespace gyrostab::firmware::target {

class CmsdkUart {
 public:
  static constexpr std::uintptr_t kUart0 = 0x40004000u;

  explicit CmsdkUart(std::uintptr_t base = kUart0) : base_(base) {}

  // 25 MHz / 16: the fastest the peripheral allows (QEMU ignores the rate).
  void start() {
    cortex_m4::reg(base_ + kBaudDiv) = 16;
    cortex_m4::reg(base_ + kCtrl) = kTxEnable | kRxEnable;
  }

  bool write(const std::uint8_t* buf, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      while ((cortex_m4::reg(base_ + kState) & kTxFull) != 0u) {
      }
      cortex_m4::reg(base_ + kData) = buf[i];
    }
    return true;
  }

  // Waits for one byte, then takes what else is there without waiting (at most n).
  std::size_t read_some(std::uint8_t* buf, std::size_t n) {
    if (n == 0) return 0;
    while ((cortex_m4::reg(base_ + kState) & kRxFull) == 0u) {
    }
    std::size_t got = 0;
    while (got < n && (cortex_m4::reg(base_ + kState) & kRxFull) != 0u) {
      buf[got++] = static_cast<std::uint8_t>(cortex_m4::reg(base_ + kData) & 0xFFu);
    }
    return got;
  }

 private:
  static constexpr std::uintptr_t kData = 0x00;
  static constexpr std::uintptr_t kState = 0x04;
  static constexpr std::uintptr_t kCtrl = 0x08;
  static constexpr std::uintptr_t kBaudDiv = 0x10;
  static constexpr std::uint32_t kTxFull = 1u << 0;
  static constexpr std::uint32_t kRxFull = 1u << 1;
  static constexpr std::uint32_t kTxEnable = 1u << 0;
  static constexpr std::uint32_t kRxEnable = 1u << 1;
  std::uintptr_t base_;
};

}  // namespace gyrostab::firmware::target
