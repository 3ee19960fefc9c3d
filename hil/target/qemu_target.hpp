// The emulated target: one QEMU process running a controller image (docs/pil.md), and the byte stream to it.
//   qemu-system-arm -M mps2-an500 -cpu cortex-m7        (mps2-an386 -cpu cortex-m4: the Cortex-M4F build)
//                   -nographic -monitor none -kernel IMAGE
//                   -icount shift=0,sleep=off          deterministic: 1 instruction = 1 ns of virtual time
//                   -semihosting-config enable=on,target=native,arg=DEVICE,arg=fifo|uart
//                   -serial pipe:uart | -serial none
// started with posix_spawn (an argument vector, no shell) in a private directory made with mkdtemp under
// $TMPDIR, which holds the link's two FIFOs (the image opens them by relative name through semihosting, or
// QEMU connects UART0 to uart.in / uart.out) and what QEMU prints (qemu.log), nothing else; it is removed when
// the link closes. The host opens its ends O_RDWR, so neither open blocks on the other side and a write never raises SIGPIPE.
// The emulator's death is watched through a pidfd: a read that would wait for a dead emulator returns at once
// with the exit status. close() ends the emulator (SIGKILL: QEMU ignores SIGTERM while the guest blocks in a
// semihosting read), reaps it and removes the directory.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gyrostab::hil {

struct QemuLaunch {
  std::string qemu{"qemu-system-arm"};
  std::string machine{"mps2-an500"};  // mps2-an500 (Cortex-M7) or mps2-an386 (Cortex-M4F)
  std::string cpu{"cortex-m7"};
  std::string image;                // the controller image (ELF)
  std::string device;               // passed to the image as its first argument
  bool uart{false};                 // the board's UART instead of semihosting FIFOs
  std::vector<std::string> extra;   // more QEMU arguments (tests)
};

enum class ByteWait { kData, kTimeout, kExited, kError };

class QemuTarget {
 public:
  QemuTarget() = default;
  QemuTarget(const QemuTarget&) = delete;
  QemuTarget& operator=(const QemuTarget&) = delete;
  ~QemuTarget() { close(); }

  // Makes the directory and FIFOs, starts QEMU. false: `error` says why (nothing is left behind).
  bool start(const QemuLaunch& launch, std::string& error);

  // Writes every byte, waiting at most until CLOCK_MONOTONIC deadline_ns for room in the FIFO. false: the
  // emulator is gone or does not read.
  bool write(const std::uint8_t* data, std::size_t n, std::int64_t deadline_ns);

  // Waits until deadline_ns for bytes; kData: `got` bytes are in buf.
  ByteWait read(std::uint8_t* buf, std::size_t n, std::int64_t deadline_ns, std::size_t& got);

  // Whether the emulator has exited (reaps it); its status in words ("exited with status 3", "killed by
  // SIGKILL").
  bool exited();
  const std::string& exit_text() const { return exit_text_; }
  // The last line the emulator printed ("" if none), e.g. why it could not load the image.
  std::string last_words() const;
  int exit_status() const { return exit_status_; }  // -1: killed by a signal or still running

  // Waits until deadline_ns for the emulator to exit by itself; true if it did.
  bool wait_exit(std::int64_t deadline_ns);

  // Fault injection (tests): stop or kill the emulator.
  void freeze();
  void kill_now();

  // Ends the emulator if it still runs, reaps it, removes the FIFOs and the directory. Idempotent.
  void close();

  pid_t pid() const { return pid_; }
  const std::string& command_line() const { return command_line_; }

 private:
  void note_status(int wstatus);

  pid_t pid_{-1};
  int pidfd_{-1};
  int to_fd_{-1};
  int from_fd_{-1};
  std::string dir_;
  std::vector<std::string> fifos_;
  std::string command_line_;
  std::string log_path_;
  std::string last_words_;
  std::string exit_text_;
  int exit_status_{-1};
  bool reaped_{false};
};

}  // namespace gyrostab::hil
