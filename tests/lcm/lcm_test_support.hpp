// Support for the `lcm` label: tests that run the gyrostab program as plant and controller processes over
// LCM udpm://. Each test executable moves itself into a private network namespace before anything else
// (unshare(CLONE_NEWNET); lo up, multicast on, 224.0.0.0/4 routed to lo — docs/architecture.md, messages and
// transports), so no datagram leaves
// the process tree and parallel tests never share a bus. Where that is not permitted (not root, no
// CAP_SYS_ADMIN, a seccomp profile) the test prints why and exits 77, which ctest reports as skipped.
// The processes it starts inherit the namespace. Plots are switched off (GYROSTAB_PLOT_SCRIPT=/dev/null).
#pragma once

#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/json_file.hpp"

#ifndef GYROSTAB_BIN
#define GYROSTAB_BIN ""
#endif

namespace gyrostab::testing {

inline constexpr int kSkip = 77;

// Enters a private network namespace with multicast on lo. "" on success, else why not.
inline std::string enter_private_network() {
  if (std::string(GYROSTAB_BIN).empty())
    return "the gyrostab program is not built (GYROSTAB_BUILD_TOOLS=OFF)";
  if (unshare(CLONE_NEWNET) != 0) {
    return std::string("unshare(CLONE_NEWNET) not permitted (") + std::strerror(errno) +
           "): these tests need root or CAP_SYS_ADMIN";
  }
  if (std::system("ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo") !=
      0) {
    return "cannot set up multicast on lo in the private namespace (is iproute2 installed?)";
  }
  return "";
}

inline int lcm_test_main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const std::string why = enter_private_network();
  if (!why.empty()) {
    std::printf("SKIP: %s\n", why.c_str());
    return kSkip;
  }
  setenv("GYROSTAB_PLOT_SCRIPT", "/dev/null", 1);
  return RUN_ALL_TESTS();
}

#define GYROSTAB_LCM_TEST_MAIN()                         \
  int main(int argc, char** argv) {                      \
    return gyrostab::testing::lcm_test_main(argc, argv); \
  }

inline std::string gyrostab_bin() {
  return GYROSTAB_BIN;
}

inline std::string scene(const std::string& file) {
  return std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes/" + file;
}

struct Exit {
  int code{-1};   // exit status, or -1 if killed
  int signal{0};  // the killing signal
};

// Starts `args` (args[0] is the program) with stdout/stderr going to this test's; returns the pid.
inline pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

inline Exit wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  Exit e;
  if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
  return e;
}

inline Exit run(const std::vector<std::string>& args) {
  return wait_for(spawn(args));
}

inline std::vector<std::string> cat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

inline std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}


// A fresh directory under /tmp, removed when the object goes (kept with GYROSTAB_KEEP_TEST_DIRS=1).
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/gyrostab-lcm-XXXXXX";
    path_ = mkdtemp(tmpl) ? tmpl : "/tmp";
  }
  ~TempDir() {
    if (std::getenv("GYROSTAB_KEEP_TEST_DIRS") == nullptr && path_ != "/tmp") {
      std::error_code ec;
      std::filesystem::remove_all(path_, ec);
    }
  }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// What must be bit-identical between two runs of the same scene and seed: report.json "figures" (as dumped
// text) and signals.csv.
struct Outputs {
  std::string figures;
  std::string csv;
};

inline Outputs outputs_of(const std::string& dir) {
  const nlohmann::json r = read_json(dir + "/report.json");
  return {r.contains("figures") ? r["figures"].dump() : "", read_file(dir + "/signals.csv")};
}

// `gyrostab run SCENE --ticks TICKS` in process (the reference), its outputs.
inline Outputs in_process(const std::string& scene_path, const std::string& dir, const std::string& ticks) {
  const Exit e = run({gyrostab_bin(), "run", scene_path, "--ticks", ticks, "--no-progress", "--out", dir});
  EXPECT_EQ(e.code, 0) << scene_path;
  return outputs_of(dir);
}

inline void expect_identical(const Outputs& a, const Outputs& b, const std::string& what) {
  ASSERT_FALSE(a.figures.empty()) << what;
  ASSERT_FALSE(a.csv.empty()) << what;
  EXPECT_EQ(a.figures, b.figures) << what << ": figures differ";
  EXPECT_TRUE(a.csv == b.csv) << what << ": signals.csv differs";
}

// The pids of the direct children of `parent` whose command line contains `needle` (e.g. "gyrostab plant").
inline std::vector<pid_t> children_matching(pid_t parent, const std::string& needle) {
  std::vector<pid_t> out;
  std::istringstream ids(
      read_file("/proc/" + std::to_string(parent) + "/task/" + std::to_string(parent) + "/children"));
  pid_t c = 0;
  while (ids >> c) {
    std::string cmd = read_file("/proc/" + std::to_string(c) + "/cmdline");
    for (char& ch : cmd) {
      if (ch == '\0') ch = ' ';
    }
    if (cmd.find(needle) != std::string::npos) out.push_back(c);
  }
  return out;
}

// Column `name` of a signals.csv, as text cells (exact comparison), one per row.
inline std::vector<std::string> csv_column(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    std::string cell;
    while (std::getline(h, cell, ',')) header.push_back(cell);
  }
  std::size_t col = header.size();
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) col = i;
  }
  std::vector<std::string> out;
  if (col == header.size()) return out;
  while (std::getline(in, line)) {
    std::istringstream r(line);
    std::string cell;
    for (std::size_t i = 0; i <= col && std::getline(r, cell, ','); ++i) {
    }
    out.push_back(cell);
  }
  return out;
}

}  // namespace gyrostab::testing
