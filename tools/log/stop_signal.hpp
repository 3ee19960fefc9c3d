// SIGINT / SIGTERM as a request to stop at the next tick boundary, so a logging run closes its bus log whole
// (docs/logs.md): the handler only stores the signal number; loops poll stop_signal_received() once a tick.
// A second signal of the same kind gets the default action (the handler is one-shot, SA_RESETHAND), so a
// loop that never reaches a tick boundary can still be killed with a second Ctrl-C.
//
//   StopSignalGuard guard;                 // installs the handlers; the destructor restores the previous ones
//   ... if (stop_signal_received() != 0) break; ...
#pragma once

namespace gyrostab::tools {

class StopSignalGuard {
 public:
  StopSignalGuard();   // clears any earlier request, then installs the handlers
  ~StopSignalGuard();  // restores the handlers found at construction
  StopSignalGuard(const StopSignalGuard&) = delete;
  StopSignalGuard& operator=(const StopSignalGuard&) = delete;

 private:
  struct Saved;
  Saved* saved_;
};

// 0, or the number of the first SIGINT/SIGTERM received while a guard was installed. Async-signal-safe.
int stop_signal_received();

// "SIGINT", "SIGTERM", or "signal N".
const char* signal_name(int signo);

}  // namespace gyrostab::tools
