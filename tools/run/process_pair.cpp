#include "tools/run/process_pair.hpp"

#include <signal.h>
#include <sys/prctl.h>
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

#include "hil/link/link_guard.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/run/link_settings.hpp"
#include "tools/run/output_dir.hpp"
#include "tools/run/run_mcap.hpp"

namespace gyrostab::tools {
namespace {

std::string fault_arg(const FrameFault& f) {
  return std::to_string(f.from) + ":" + std::to_string(f.count);
}

std::vector<std::string> child_args(const RunRequest& req, const std::string& role, const std::string& suffix,
                                    std::uint64_t session, std::uint64_t controller_id) {
  const TransportOptions& t = req.transport;
  std::vector<std::string> a{"gyrostab", role, req.scene_path, "--out",
                             role == "plant" ? req.out_dir : req.out_dir + "/controller"};
  // One session for both children, so the controller can bind to nobody else's plant.
  a.insert(a.end(), {"--session", format_link_id(session)});
  // And the controller's id for both: the plant accepts commands from nobody else, from the first tick on (a
  // second source speaking as it is caught as a hijack, hil/link/source_watch.hpp).
  a.insert(a.end(), {"--controller-id", format_link_id(controller_id)});
  if (!t.key_file.empty()) a.insert(a.end(), {"--key-file", t.key_file});
  // The plant decides how long the run is; the controller stops on its end-of-run frame (docs/protocol.md).
  if (req.ticks >= 0 && role == "plant") a.insert(a.end(), {"--ticks", std::to_string(req.ticks)});
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
  if (t.loss > 0) {
    char l[32];
    std::snprintf(l, sizeof l, "%.17g", t.loss);
    a.insert(a.end(), {"--loss", l});
  }
  if (role == "plant") {
    if (!t.log_path.empty()) a.insert(a.end(), {"--log", t.log_path});
    // --mcap: the plant keeps the frames and leaves them beside signals.csv for the file this parent writes.
    if (!req.mcap_path.empty() && req.mcap_frames_every != 0) {
      a.push_back("--mcap-frames-csv");
      if (req.mcap_frames_every > 0) a.insert(a.end(), {"--mcap-frames-every", std::to_string(req.mcap_frames_every)});
    }
    if (req.view.enabled) {
      // The plant process serves the view. It does not linger unless asked to: a Ctrl-C that ended its serving
      // would reach this parent too and mark a completed run as stopped.
      char wait[32], linger[32];
      std::snprintf(wait, sizeof wait, "%.17g", req.view.wait_s);
      std::snprintf(linger, sizeof linger, "%.17g", req.view.linger_s < 0 ? 0.0 : req.view.linger_s);
      a.insert(a.end(), {"--view=" + req.view.address, "--view-wait", wait, "--view-linger", linger});
    }
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

// The stop signal the parent received (SIGINT, SIGTERM), forwarded to the children by the wait loop.
volatile sig_atomic_t g_stop_signal = 0;
void on_stop_signal(int signo) { g_stop_signal = signo; }

pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // A child dies with its parent (SIGTERM: it stops at a tick boundary and writes what it has), even
    // when the parent is killed with SIGKILL; the check closes the race of a parent gone before prctl.
    if (prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || getppid() != parent) _exit(127);
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
  bool stopped_by_run{false};  // SIGTERM from the parent after the other child failed
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
    if (stopped_by_run) return std::string(name) + " stopped by the run after the other process failed";
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
  if (const std::string why = key_file_problem(req.transport); !why.empty()) {
    std::fprintf(stderr, "gyrostab run: %s\n", why.c_str());
    return 2;
  }
  std::string out_error;
  if (!check_output_dir(req.out_dir, out_error) || !check_output_dir(req.out_dir + "/controller", out_error)) {
    std::fprintf(stderr, "gyrostab run: %s\n", out_error.c_str());
    return 2;
  }
  if (!req.mcap_path.empty()) {
    if (const std::string why = mcap_path_problem(req.mcap_path); !why.empty()) {
      std::fprintf(stderr, "gyrostab run: %s\n", why.c_str());
      return 2;
    }
  }
  std::error_code ec;
  std::filesystem::remove(req.out_dir + "/report.json", ec);
  std::filesystem::remove(req.out_dir + "/controller/report.json", ec);
  std::fflush(nullptr);
  const std::uint64_t session = req.transport.session != 0 ? req.transport.session : hil::draw_link_id();
  std::uint64_t controller_id = req.transport.controller_id != 0 ? req.transport.controller_id : hil::draw_link_id();
  while (controller_id == session) controller_id = hil::draw_link_id();
  if (session == 0 || controller_id == 0) {
    std::fprintf(stderr, "gyrostab run: the OS's random source (getrandom) failed: cannot draw a session id\n");
    return 3;
  }
  // Installed before the children exist, so a stop request is never lost: the wait loop forwards it to both
  // (they stop at a tick boundary and write their outputs), then merges what they wrote.
  struct sigaction sa{};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: waitpid returns EINTR and the loop forwards at once
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  Child controller{"controller"}, plant{"plant"};
  controller.pid = spawn(child_args(req, "controller", suffix, session, controller_id));
  plant.pid = spawn(child_args(req, "plant", suffix, session, controller_id));
  if (controller.pid < 0 || plant.pid < 0) {
    std::fprintf(stderr, "gyrostab run: fork failed: %s\n", std::strerror(errno));
    if (controller.pid > 0) kill(controller.pid, SIGTERM);
    if (plant.pid > 0) kill(plant.pid, SIGTERM);
    return 3;
  }
  // A child that exits with an error leaves the other waiting for nothing: it detects that itself within its
  // receive timeout and reports it; past that (and a margin for writing its outputs) it is stopped with
  // SIGTERM. A killed child is the other's to detect (receive timeout, safe state).
  const auto now_ms = [] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  long long stop_other_at = -1;
  const Child* first_failed = nullptr;
  int forwarded = 0;
  while (!controller.done || !plant.done) {
    if (g_stop_signal != 0 && forwarded == 0) {
      forwarded = g_stop_signal;
      if (!plant.done) kill(plant.pid, forwarded);
      if (!controller.done) kill(controller.pid, forwarded);
    }
    // Polled every 10 ms, never a blocking wait: a stop signal that lands between the check above and a
    // blocking waitpid would otherwise wait for a child to end by itself.
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (pid == 0) {
      if (stop_other_at >= 0 && now_ms() >= stop_other_at) {
        Child& other = plant.done ? controller : plant;
        kill(other.pid, SIGTERM);
        other.stopped_by_run = true;
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
      first_failed = &c;
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
  const auto completed = [](const Child& c) { return c.exited() && (c.code() == 0 || c.code() == kExitForeignFrames); };
  bool foreign = false;
  // Exit 7 is also a second source on the link: that run was stopped, it did not complete.
  const bool hijacked = (have_plant && report.contains("link") && report["link"].contains("hijacked")) ||
                        (have_ctl && ctl.contains("link") && ctl["link"].contains("hijacked"));
  if (plant.exited() && controller.exited() && plant.code() == 0 && controller.code() == 0) {
    happened = "completed";
  } else if (completed(plant) && completed(controller) && !hijacked) {
    foreign = true;
    happened = "completed; frames of another session, recorded frames or frames that failed authentication were on "
               "the link and refused, none acted on (link.session.refused, controller_process.link.session.refused)";
  } else {
    happened = (hijacked ? std::string("stopped on a second source: ") : std::string()) + plant.how() + ", " +
               controller.how();
    if (have_plant && report.contains("link"))
      happened += "; plant: " + report["link"].value("what_happened", "");
    if (have_ctl && ctl.contains("link"))
      happened += "; controller: " + ctl["link"].value("what_happened", "");
  }
  // Lockstep is the in-process run bit for bit unless a command does not arrive: that tick gets zero torque
  // (the drive watchdog) and the loop goes on. Without an injected fault that is not this scene's run — a
  // second pair on the bus that kept the sets from completing, say — and the run does not pass as completed.
  const TransportOptions& t = req.transport;
  const bool fault_injected = t.loss > 0 || t.jitter_max_us > 0 || t.sensor_drop.from >= 0 ||
                              t.sensor_corrupt.from >= 0 || t.actuator_drop.from >= 0 || t.actuator_corrupt.from >= 0;
  const std::int64_t zero_torque_ticks =
      have_plant && report.contains("link") && report["link"].contains("drive_watchdog")
          ? report["link"]["drive_watchdog"].value("zero_torque_ticks", std::int64_t{0})
          : 0;
  bool degraded = false;
  if (completed(plant) && completed(controller) && !t.real_time && !fault_injected && zero_torque_ticks > 0) {
    degraded = true;
    happened = "degraded: " + std::to_string(zero_torque_ticks) +
               " ticks got zero torque because their command did not arrive in time (link.drive_watchdog), with no "
               "fault injected: not the lockstep run of this scene" +
               (foreign ? "; " + happened : std::string());
  }
  if (forwarded != 0) happened = std::string("stopped by ") + signal_name(forwarded) + "; " + happened;
  report["processes"] = {{"transport", req.transport.transport},
                         {"lcm_url", req.transport.lcm_url},
                         {"channel_suffix", suffix},
                         {"session", format_link_id(session)},
                         {"plant", plant.json()},
                         {"controller", controller.json()},
                         {"what_happened", happened}};
  if (!write_file_atomic(req.out_dir + "/report.json", report.dump(2) + "\n", out_error)) {
    std::fprintf(stderr, "gyrostab run: %s\n", out_error.c_str());
    return 3;
  }
  // --mcap: from the plant's signals.csv and the merged report, so the file's report is report.json.
  if (!req.mcap_path.empty() && have_plant) {
    if (!write_mcap_from_outputs(req.mcap_path, req.out_dir, report, out_error)) {
      std::fprintf(stderr, "gyrostab run: %s\n", out_error.c_str());
      return 3;
    }
    std::printf("%s: wrote %s\n", req.scene_path.c_str(), req.mcap_path.c_str());
  }
  if (happened == "completed") {
    std::printf("%s: wrote %s/report.json, signals.csv (plant and controller over %s)\n",
                req.scene_path.c_str(), req.out_dir.c_str(),
                req.transport.transport == "can" ? "CAN" : "LCM");
    return 0;
  }
  std::fprintf(stderr, "gyrostab run: %s\n", happened.c_str());
  if (forwarded != 0) return 128 + forwarded;
  if (degraded) return kExitDegraded;
  if (foreign) return kExitForeignFrames;
  // The child that failed first says why; the other was only stopped because of it.
  if (first_failed != nullptr && (plant.stopped_by_run || controller.stopped_by_run))
    return first_failed->exited() ? first_failed->code() : kExitPeerLost;
  if (plant.killed() || controller.killed()) return kExitPeerLost;
  if (plant.code() != 0) return plant.code();
  return controller.code();
}

}  // namespace gyrostab::tools
