// Support for the `hil` label: tests that need a real SocketCAN interface (vcan0). A test executable started
// anywhere re-executes itself through hil/vcan-run — natively in a private network namespace with vcan0 where
// the kernel has CAN, else inside the small qemu VM (hil/vm/run-in-vm, this build's vm-cache) with the gyrostab
// program, the source tree and the build tree visible at their own paths — and returns its exit code. Inside,
// GYROSTAB_VCAN_MODE (native | vm) and GYROSTAB_CAN_IF (vcan0) are set and the tests run. Plots are off.
// The process helpers (spawn, run, TempDir, read_json, ...) are the lcm label's (tests/lcm/lcm_test_support.hpp).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/lcm/lcm_test_support.hpp"

#ifndef GYROSTAB_BINARY_DIR
#define GYROSTAB_BINARY_DIR ""
#endif

namespace gyrostab::testing {

inline std::string can_if() {
  const char* i = std::getenv("GYROSTAB_CAN_IF");
  return i != nullptr ? i : "vcan0";
}

// Waits until some process on the interface receives `id` through a kernel filter (a gyrostab process has
// opened its socket): the rows of /proc/net/can/rcvlist_fil and rcvlist_sff. false after `timeout_ms`.
// id < 0: any socket without a filter (candump), the rows of rcvlist_all.
inline bool wait_for_can_listener(int id, int timeout_ms = 30000) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "%x", static_cast<unsigned>(id));
  for (int waited = 0; waited < timeout_ms; waited += 20) {
    const std::vector<const char*> lists =
        id < 0 ? std::vector<const char*>{"/proc/net/can/rcvlist_all"}
               : std::vector<const char*>{"/proc/net/can/rcvlist_fil", "/proc/net/can/rcvlist_sff"};
    for (const char* list : lists) {
      std::istringstream in(read_file(list));
      std::string line;
      while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string dev, can_id;
        if (words >> dev >> can_id && dev == can_if() && (id < 0 || can_id == hex)) return true;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

inline int hil_test_main(int argc, char** argv) {
  if (std::getenv("GYROSTAB_VCAN_MODE") == nullptr) {
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) {
      std::perror("readlink /proc/self/exe");
      return 2;
    }
    self[n] = '\0';
    std::vector<std::string> args{std::string(GYROSTAB_SOURCE_DIR) + "/hil/vcan-run", "--build", GYROSTAB_BINARY_DIR,
                                  "--share", GYROSTAB_SOURCE_DIR, "--share", GYROSTAB_BINARY_DIR, "--timeout", "850"};
    if (!gyrostab_bin().empty()) args.insert(args.end(), {"--bin", gyrostab_bin()});
    args.insert(args.end(), {"--", self});
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    std::vector<char*> cargv;
    for (auto& a : args) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    std::fflush(nullptr);
    execv(cargv[0], cargv.data());
    std::perror("exec hil/vcan-run");
    return 2;
  }
  ::testing::InitGoogleTest(&argc, argv);
  setenv("GYROSTAB_PLOT_SCRIPT", "", 1);  // the VM has no python3: plots off
  std::printf("hil: %s on %s\n", std::getenv("GYROSTAB_VCAN_MODE"), can_if().c_str());
  return RUN_ALL_TESTS();
}

#define GYROSTAB_HIL_TEST_MAIN() \
  int main(int argc, char** argv) { return gyrostab::testing::hil_test_main(argc, argv); }

}  // namespace gyrostab::testing
