#include "tools/run/process_pair.hpp"

#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "tools/run/link_settings.hpp"

namespace gyrostab::tools {
namespace {

std::string fault_arg(const FrameFault& f) {
  return std::to_string(f.from) + ":" + std::to_string(f.count);
}

std::vector<std::string> child_args(const RunRequest& req, const std::string& role,
                                    const std::string& suffix) {
  const TransportOptions& t = req.transport;
  std::vector<std::string> a{"gyrostab", role, req.scene_path, "--out",
                             role == "plant" ? req.out_dir : req.out_dir + "/controller"};
  if (req.ticks >= 0) a.insert(a.end(), {"--ticks", std::to_string(req.ticks)});
  if (!t.lcm_actuator_url.empty()) a.insert(a.end(), {"--lcm-actuator-url", t.lcm_actuator_url});
  a.insert(a.end(), {"--lcm-url", t.lcm_url, "--channel-suffix", suffix, "--timeout-ms",
                     std::to_string(t.timeout_ms), "--start-timeout-ms", std::to_string(t.start_timeout_ms)});
  if (t.transport == "can") {  // CAN FD over SocketCAN: both children on the same interface
    char rate[32], data_rate[32];
    std::snprintf(rate, sizeof rate, "%.17g", t.can_bitrate);
    std::snprintf(data_rate, sizeof data_rate, "%.17g", t.can_data_bitrate);
    a.insert(a.end(), {"--can-if", t.can_if.empty() ? std::string("vcan0") : t.can_if, "--can-bitrate", rate,
                       "--can-data-bitrate", data_rate});
    if (!t.can_filter) a.push_back("--can-no-filter");
    if (role == "plant" && !t.can_log.empty()) a.insert(a.end(), {"--can-log", t.can_log});
  }
  if (t.real_time) {
    a.insert(a.end(), {"--real-time", "--spin-us", std::to_string(t.spin_us), "--rt-priority",
                       std::to_string(t.rt_priority)});
  }
  if (role == "plant") {
    if (!t.log_path.empty()) a.insert(a.end(), {"--log", t.log_path});
    if (t.sensor_drop.from >= 0) a.insert(a.end(), {"--drop-sensor", fault_arg(t.sensor_drop)});
    if (t.sensor_corrupt.from >= 0) a.insert(a.end(), {"--corrupt-sensor", fault_arg(t.sensor_corrupt)});
  } else {
    if (t.jitter_max_us > 0) {
      char j[64];
      std::snprintf(j, sizeof j, "%.17g@%.17g", t.jitter_max_us, t.jitter_probability);
      a.insert(a.end(), {"--jitter", j});
    }
    if (t.actuator_drop.from >= 0) a.insert(a.end(), {"--drop-actuator", fault_arg(t.actuator_drop)});
    if (t.actuator_corrupt.from >= 0)
      a.insert(a.end(), {"--corrupt-actuator", fault_arg(t.actuator_corrupt)});
  }
  return a;
}

pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    execv("/proc/self/exe", argv.data());
    std::fprintf(stderr, "gyrostab run: cannot exec /proc/self/exe: %s\n", std::strerror(errno));
    _exit(127);
  }
  return pid;
}

struct Child {
  const char* name;
  pid_t pid{-1};
  bool done{false};
  int status{0};
  bool exited() const { return done && WIFEXITED(status); }
  bool killed() const { return done && WIFSIGNALED(status); }
  int code() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
  nlohmann::json json() const {
    nlohmann::json j{{"pid", pid}};
    if (exited()) j["exit_code"] = code();
    if (killed()) j["killed_by_signal"] = WTERMSIG(status);
    return j;
  }
  std::string how() const {
    if (killed()) return std::string(name) + " killed by signal " + std::to_string(WTERMSIG(status));
    return std::string(name) + " exited with " + std::to_string(code());
  }
};

bool read_json(const std::string& path, nlohmann::json& out) {
  std::ifstream f(path);
  if (!f) return false;
  out = nlohmann::json::parse(f, nullptr, false);
  return !out.is_discarded();
}

}  // namespace

int run_process_pair(const RunRequest& req) {
  const std::string suffix =
      req.transport.channel_suffix.empty() ? "_" + std::to_string(getpid()) : req.transport.channel_suffix;
  std::error_code ec;
  std::filesystem::create_directories(req.out_dir + "/controller", ec);
  std::filesystem::remove(req.out_dir + "/report.json", ec);
  std::filesystem::remove(req.out_dir + "/controller/report.json", ec);
  std::fflush(nullptr);
  Child controller{"controller"}, plant{"plant"};
  controller.pid = spawn(child_args(req, "controller", suffix));
  plant.pid = spawn(child_args(req, "plant", suffix));
  if (controller.pid < 0 || plant.pid < 0) {
    std::fprintf(stderr, "gyrostab run: fork failed: %s\n", std::strerror(errno));
    if (controller.pid > 0) kill(controller.pid, SIGTERM);
    if (plant.pid > 0) kill(plant.pid, SIGTERM);
    return 3;
  }
  // The parent only waits: a Ctrl-C reaches the children through the terminal's process group and they stop
  // at a tick boundary; the parent must outlive them to merge their reports.
  signal(SIGINT, SIG_IGN);
  signal(SIGTERM, SIG_IGN);
  // A child that exits with an error leaves the other waiting for nothing: it detects that itself within its
  // receive timeout and reports it; past that (and a margin for writing its outputs) it is stopped with
  // SIGTERM. A killed child is the other's to detect (receive timeout, safe state).
  const auto now_ms = [] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  long long stop_other_at = -1;
  while (!controller.done || !plant.done) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, stop_other_at >= 0 ? WNOHANG : 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (pid == 0) {
      if (now_ms() >= stop_other_at) {
        kill(plant.done ? controller.pid : plant.pid, SIGTERM);
        stop_other_at = -1;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      continue;
    }
    Child& c = pid == plant.pid ? plant : controller;
    c.done = true;
    c.status = status;
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0 && (!plant.done || !controller.done)) {
      stop_other_at = now_ms() + req.transport.timeout_ms + 2000;
    }
  }

  nlohmann::json report, ctl;
  const bool have_plant = read_json(req.out_dir + "/report.json", report);
  const bool have_ctl = read_json(req.out_dir + "/controller/report.json", ctl);
  if (!have_plant) report = nlohmann::json::object();
  if (have_ctl) {
    if (ctl.contains("timing") && ctl["timing"].contains("controller")) {
      report["timing"]["controller"] = ctl["timing"]["controller"];
      ctl["timing"].erase("controller");
    }
    report["controller_process"] = ctl;
  }
  std::string happened;
  if (plant.exited() && controller.exited() && plant.code() == 0 && controller.code() == 0) {
    happened = "completed";
  } else {
    happened = plant.how() + ", " + controller.how();
    if (have_plant && report.contains("link"))
      happened += "; plant: " + report["link"].value("what_happened", "");
    if (have_ctl && ctl.contains("link"))
      happened += "; controller: " + ctl["link"].value("what_happened", "");
  }
  report["processes"] = {{"transport", req.transport.transport},
                         {"lcm_url", req.transport.lcm_url},
                         {"channel_suffix", suffix},
                         {"plant", plant.json()},
                         {"controller", controller.json()},
                         {"what_happened", happened}};
  {
    std::ofstream f(req.out_dir + "/report.json");
    f << report.dump(2) << "\n";
    if (!f) {
      std::fprintf(stderr, "gyrostab run: cannot write %s/report.json\n", req.out_dir.c_str());
      return 3;
    }
  }
  if (happened == "completed") {
    std::printf("%s: wrote %s/report.json, signals.csv (plant and controller over %s)\n",
                req.scene_path.c_str(), req.out_dir.c_str(),
                req.transport.transport == "can" ? "CAN" : "LCM");
    return 0;
  }
  std::fprintf(stderr, "gyrostab run: %s\n", happened.c_str());
  if (plant.killed() || controller.killed()) return kExitPeerLost;
  if (plant.code() != 0) return plant.code();
  return controller.code();
}

}  // namespace gyrostab::tools
