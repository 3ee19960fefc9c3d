// Real-time process set-up for `--real-time`: lock all memory (mlockall: no page fault in the loop) and run
// under SCHED_FIFO at `priority` (threads created later — LCM's receive thread — inherit it). Each step that
// the system refuses (no CAP_SYS_NICE / CAP_IPC_LOCK, an RLIMIT, a container) is reported in one line and the
// run goes on without it. Call before opening the transport.
#pragma once

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace gyrostab::hil {

struct RtSetup {
  bool memory_locked{false};
  bool fifo{false};
  int priority{0};
  std::string message;  // one line, for stderr and the report
};

inline RtSetup setup_real_time(int priority) {
  RtSetup r;
  r.priority = priority;
  std::string lock_msg, fifo_msg;
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    r.memory_locked = true;
    lock_msg = "mlockall ok";
  } else {
    lock_msg = std::string("mlockall not permitted (") + std::strerror(errno) + "), memory may page";
  }
  if (priority <= 0) {
    fifo_msg = "SCHED_FIFO not requested (--rt-priority 0)";
  } else {
    sched_param p{};
    p.sched_priority = priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
      r.fifo = true;
      fifo_msg = "SCHED_FIFO " + std::to_string(priority) + " ok";
    } else {
      fifo_msg = std::string("SCHED_FIFO not permitted (") + std::strerror(errno) +
                 "), running at normal priority: expect more jitter";
    }
  }
  r.message = "real time: " + fifo_msg + "; " + lock_msg;
  return r;
}

}  // namespace gyrostab::hil
