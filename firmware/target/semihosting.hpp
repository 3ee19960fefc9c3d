// ARM semihosting (Arm, "Semihosting for AArch32 and AArch64", v3.0): the debugger's (here QEMU's) calls into
// the host, entered with `bkpt 0xAB` on M-profile cores, r0 = operation, r1 = parameter block. The controller
// images use it as the fast lockstep channel to the plant (two host FIFOs, see docs/pil.md: QEMU 7.2's CMSDK
// UART moves one byte per main-loop turn, a few hundred frames per second) and to end the emulation with an
// exit code. Only valid when the emulator enables semihosting (-semihosting-config enable=on): on a board
// without a debugger the bkpt stops the core, so an image calls these only when told to by the link choice
// (firmware/target/target_channel.hpp). No heap; each call is one trap.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gyrostab::firmware::target::semihosting {

enum class Op : std::uint32_t {
  kOpen = 0x01,
  kWrite = 0x05,
  kRead = 0x06,
  kGetCmdline = 0x15,
  kExitExtended = 0x20,
};

inline std::int32_t call(Op op, const void* block) {
  register std::uint32_t r0 __asm__("r0") = static_cast<std::uint32_t>(op);
  register const void* r1 __asm__("r1") = block;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return static_cast<std::int32_t>(r0);
}

// Opens a host file (relative names: the emulator's working directory). mode: 1 = "rb", 5 = "wb".
// Returns the handle, or -1.
inline std::int32_t open(const char* path, std::uint32_t mode) {
  std::size_t n = 0;
  while (path[n] != '\0') ++n;
  const std::uint32_t block[3] = {static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(path)), mode,
                                  static_cast<std::uint32_t>(n)};
  return call(Op::kOpen, block);
}

// Reads up to n bytes (blocks until at least one, as the host's read(2) on a FIFO does). Returns the number
// read; 0 at end of file (the host closed its end).
inline std::size_t read(std::int32_t handle, std::uint8_t* buf, std::size_t n) {
  const std::uint32_t block[3] = {static_cast<std::uint32_t>(handle),
                                  static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(buf)),
                                  static_cast<std::uint32_t>(n)};
  const std::int32_t not_read = call(Op::kRead, block);
  return not_read < 0 || static_cast<std::size_t>(not_read) > n ? 0 : n - static_cast<std::size_t>(not_read);
}

// Writes n bytes. true when all were written.
inline bool write(std::int32_t handle, const std::uint8_t* buf, std::size_t n) {
  const std::uint32_t block[3] = {static_cast<std::uint32_t>(handle),
                                  static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(buf)),
                                  static_cast<std::uint32_t>(n)};
  return call(Op::kWrite, block) == 0;
}

// The command line the emulator was given for the program (QEMU: the arg= values of -semihosting-config),
// NUL-terminated into buf. false if there is none or it does not fit.
inline bool command_line(char* buf, std::size_t n) {
  std::uint32_t block[2] = {static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(buf)),
                            static_cast<std::uint32_t>(n)};
  return call(Op::kGetCmdline, block) == 0;
}

// Ends the emulation with this exit status (ADP_Stopped_ApplicationExit with a subcode).
[[noreturn]] inline void exit(std::uint32_t status) {
  const std::uint32_t block[2] = {0x20026u, status};
  call(Op::kExitExtended, block);
  for (;;) __asm__ volatile("wfi");
}

}  // namespace gyrostab::firmware::target::semihosting
