// gyrostab — command-line entry point: demo, run, plant, controller, check, replay, accuracy, sweep, view, export, ...
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/accuracy/accuracy_command.hpp"
#include "tools/commands.hpp"
#include "tools/dbc_command.hpp"
#include "tools/demo_gimbal_gyro.hpp"
#include "tools/log/bus_log_export.hpp"
#include "tools/motion_record_command.hpp"
#include "tools/replay_command.hpp"
#include "tools/run/link_cli.hpp"
#include "tools/run/process_pair.hpp"
#include "tools/scene/scene_keys.hpp"
#include "tools/sweep/merge.hpp"
#include "tools/sweep/sweep_command.hpp"
#include "tools/view/lcm_view.hpp"
#include "hil/lcm/lcm_transport.hpp"

#ifndef GYROSTAB_VERSION
#define GYROSTAB_VERSION "unknown"
#endif

namespace {

// Levenshtein distance: the subcommand a mistyped one was probably meant to be.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// An unknown first word: say which subcommand it is closest to instead of CLI11's "A subcommand is
// required". true if it printed a message (exit 2).
bool refuse_unknown_subcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string word = argv[1];
  std::string best;
  std::size_t best_d = 1000;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    if (sub->get_name() == word) return false;
    const std::size_t d = edit_distance(word, sub->get_name());
    if (d < best_d) {
      best_d = d;
      best = sub->get_name();
    }
  }
  std::fprintf(stderr, "gyrostab: '%s' is not a command%s (gyrostab --help lists them)\n", word.c_str(),
               best_d <= 2 ? ("; did you mean '" + best + "'?").c_str() : "");
  return true;
}

// --mcap and --view: the run as an MCAP file, and its live view in the browser.
CLI::Option* add_live_options(CLI::App* cmd, gyrostab::tools::RunRequest& r) {
  cmd->add_option("--mcap", r.mcap_path,
                  "also write the run as an MCAP file (recorded signals, sensor and actuator frames, report; "
                  "Foxglove, Lichtblick, PlotJuggler; docs/mcap.md)");
  cmd->add_option("--mcap-frames-every", r.mcap_frames_every,
                  "with --mcap: the frame channels hold every N-th tick's frames (default: the recorded rows' "
                  "ticks, [output] record_every; 1: every tick; 0: no frame channels)")
      ->check(CLI::NonNegativeNumber);
  CLI::Option* view = cmd->add_option("--view", r.view.address,
                                      "serve a live view of the run in the browser at [ADDR:PORT] (default "
                                      "127.0.0.1 on a free port; the URL with its token is printed; docs/view.md)")
                          ->expected(0, 1);
  cmd->add_option("--view-wait", r.view.wait_s, "with --view: wait at most this long [s] for a page before tick 0");
  cmd->add_option("--view-linger", r.view.linger_s,
                  "with --view: keep serving this long [s] after the run (negative: until Ctrl-C)");
  return view;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gyrostab: gyroscopic stabilizers and gimbal drives"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("gyrostab ") + GYROSTAB_VERSION);
  app.option_defaults()->always_capture_default();  // help shows every option's default

  gyrostab::tools::DemoOptions demo;
  CLI::App* demo_cmd = app.add_subcommand(
      "demo", "simulate a gimbal gyro pendulum and print its nutation and precession frequencies against Magnus");
  demo_cmd->add_option("--rpm", demo.rpm, "rotor speed [rpm]")->check(CLI::PositiveNumber);
  demo_cmd->add_option("--CR", demo.CR, "rotor axial moment C^R [kg m^2]")->check(CLI::PositiveNumber);
  demo_cmd->add_option("--A", demo.A, "outer-axis moment A [kg m^2]")->check(CLI::PositiveNumber);
  demo_cmd->add_option("--B", demo.B, "inner-axis moment B [kg m^2]")->check(CLI::PositiveNumber);
  demo_cmd->add_option("--Gs", demo.Gs, "unbalance Gs [N m], < 0 pendulous");
  demo_cmd->add_option("--tick-us", demo.tick_us, "controller tick [us]")->check(CLI::PositiveNumber);
  demo_cmd->add_option("--substeps", demo.substeps, "plant steps per tick")->check(CLI::Range(1, 100000));
  demo_cmd->add_option("--method", demo.method, "gyro-exponential | rk4 | implicit-midpoint");
  demo_cmd->add_flag("--force", demo.force, "run even if the step validation refuses the step");

  gyrostab::tools::RunRequest run;
  CLI::App* run_cmd = app.add_subcommand("run", "run a scene in one process (plant + firmware) and write its outputs");
  run_cmd->add_option("scene", run.scene_path, "scene file (TOML)")->required();
  run_cmd->add_option("--out", run.out_dir, "output directory (report.json, signals.csv, signals.png)");
  run_cmd->add_flag("!--no-progress", run.progress, "no progress line on the terminal");
  run_cmd->add_option("--log", run.transport.log_path,
                      "record the bus as an LCM event log (docs/logs.md); SIGINT/SIGTERM stop at a tick boundary");
  gyrostab::tools::add_link_options(run_cmd, run, gyrostab::tools::LinkSide::kRun);  // --transport lcm|can, the link options
  CLI::Option* run_view = add_live_options(run_cmd, run);

  // Plant and controller as two processes over LCM (docs/transport.md).
  gyrostab::tools::RunRequest plant;
  plant.role = gyrostab::tools::Role::kPlant;
  plant.progress = false;
  CLI::App* plant_cmd = app.add_subcommand(
      "plant", "run the plant of a scene as its own process, exchanging frames with `gyrostab controller` over LCM");
  plant_cmd->add_option("scene", plant.scene_path, "scene file (TOML), the same as the controller's")->required();
  plant_cmd->add_option("--out", plant.out_dir, "output directory (report.json, signals.csv, signals.png)");
  plant_cmd->add_option("--log", plant.transport.log_path, "record the bus as an LCM event log (docs/logs.md)");
  gyrostab::tools::add_link_options(plant_cmd, plant, gyrostab::tools::LinkSide::kPlant);
  CLI::Option* plant_view = add_live_options(plant_cmd, plant);
  // For `run --transport lcm|can --mcap`: the frames beside signals.csv, for the parent's MCAP file.
  plant_cmd->add_flag("--mcap-frames-csv", plant.mcap_frames_csv)->group("");
  gyrostab::tools::RunRequest controller;
  controller.role = gyrostab::tools::Role::kController;
  controller.progress = false;
  CLI::App* controller_cmd = app.add_subcommand(
      "controller", "run the firmware controller of a scene as its own process, the other end of `gyrostab plant`");
  controller_cmd->add_option("scene", controller.scene_path, "scene file (TOML), the same as the plant's")->required();
  controller_cmd->add_option("--out", controller.out_dir, "output directory (report.json)");
  gyrostab::tools::add_link_options(controller_cmd, controller, gyrostab::tools::LinkSide::kController);

  gyrostab::tools::RunRequest check;
  check.check_only = true;
  CLI::App* check_cmd = app.add_subcommand("check", "validate a scene without running it");
  check_cmd->add_option("scene", check.scene_path, "scene file (TOML)")->required();

  gyrostab::tools::RunRequest replay;
  replay.role = gyrostab::tools::Role::kReplay;
  replay.write_outputs = false;
  replay.progress = false;
  bool resimulate = false;
  CLI::App* replay_cmd = app.add_subcommand(
      "replay", "replay a bus log into the controller alone and check every actuator frame bit for bit "
                "(exit 0 identical, 4 mismatch, 5 truncated/corrupt log, 2 nothing replayed)");
  replay_cmd->add_option("log", replay.transport.replay_log, "bus log (gyrostab run --log) or candump log (--can-log)")->required();
  replay_cmd->add_option("--scene", replay.scene_path, "use this scene instead of the one recorded in the log");
  replay_cmd->add_flag("--real-time", replay.transport.replay_real_time, "feed frames at the scene's tick rate");
  bool replay_target = false;
  replay_cmd->add_flag("--target", replay_target,
                       "replay into the device's firmware image on the emulated Cortex-M7 (QEMU, docs/pil.md) "
                       "instead of the host build of the controller");
  replay_cmd->add_option("--target-image", replay.transport.target_image, "with --target: run this image")
      ->check(CLI::ExistingFile);
  replay_cmd->add_option("--qemu", replay.transport.qemu, "with --target: the emulator (default qemu-system-arm)");
  replay_cmd->add_option("--timeout-ms", replay.transport.timeout_ms,
                         "with --target: the image is lost after this long without an answer (default 1000)")
      ->check(CLI::PositiveNumber);
  replay_cmd->add_flag("--resimulate", resimulate,
                       "re-simulate the plant open loop from the recorded actuator frames and check every sensor "
                       "frame (exit 3 if the plant diverges where the run did not)");
  CLI::Option* replay_out =
      replay_cmd->add_option("--out", replay.out_dir, "with --resimulate: write the re-simulated run's outputs here");

  gyrostab::tools::AccuracyRequest accuracy;
  CLI::App* accuracy_cmd = app.add_subcommand(
      "accuracy", "error against run time: the scene's plant by our integrators and by Boost.Odeint and SUNDIALS "
                  "CVODE, work-precision table, accuracy.csv, report.json, work_precision.png (docs/accuracy.md)");
  accuracy_cmd->add_option("scene", accuracy.scene_path, "scene file (TOML)")->required();
  accuracy_cmd->add_option("--out", accuracy.out_dir, "output directory");
  accuracy_cmd->add_option("--duration", accuracy.duration_s, "window from t = 0 [s] (default: docs/accuracy.md)")
      ->check(CLI::PositiveNumber);
  accuracy_cmd->add_option("--repeats", accuracy.repeats, "timings per run")->check(CLI::Range(1, 100));
  accuracy_cmd->add_flag("--quick", accuracy.quick, "a small grid and one repeat (tests)");
  accuracy_cmd->add_flag("!--no-plot", accuracy.plot, "no work_precision.png");
  accuracy_cmd->add_flag("!--no-progress", accuracy.progress, "no progress line");

  // A sizing study over a sea-state table (docs/sweep.md); `sweep merge DIR` merges a study directory.
  gyrostab::tools::sweep::SweepRequest sweep;
  CLI::App* sweep_cmd = app.add_subcommand(
      "sweep", "run a sizing study: every sea state x variant x seed of a study file, in process on N threads, "
               "then merge (exit 0 all completed, 2 refused, 3 tasks failed, 4 tasks missing; docs/sweep.md)");
  sweep_cmd->add_option("study", sweep.study_path, "study file (TOML)");
  sweep_cmd->add_option("--out", sweep.out_dir, "study directory (task files, study.json, results/)");
  sweep_cmd->add_option("--jobs", sweep.jobs, "threads (default: the number of cores)")->check(CLI::Range(1, 1024));
  sweep_cmd->add_option("--shard", sweep.shard, "I/N: run only the tasks whose index mod N is I-1, and do not merge");
  sweep_cmd->add_flag("--quiet", sweep.quiet, "no progress");
  CLI::Option* sweep_view =
      sweep_cmd->add_option("--view", sweep.view_address,
                            "serve a live view of the sweep (progress, heat maps as cells finish) at [ADDR:PORT] "
                            "(default 127.0.0.1 on a free port; docs/view.md)")
          ->expected(0, 1);
  sweep_cmd->add_option("--view-linger", sweep.view_linger_s,
                        "with --view: keep serving this long [s] after the sweep (negative: until Ctrl-C)");
  std::string merge_dir;
  CLI::App* merge_cmd = sweep_cmd->add_subcommand(
      "merge", "merge a study directory's task files into results/ (tables, summaries, heat maps) and timing.json");
  merge_cmd->add_option("dir", merge_dir, "study directory")->required();

  // The DBC file of a device's CAN bus (docs/can.md): written from the map its signal table generates.
  gyrostab::tools::DbcRequest dbc;
  CLI::App* dbc_cmd = app.add_subcommand(
      "dbc", "write the DBC file of a device's CAN FD bus (its map: ids, lengths, signals, scaling, units, ranges)");
  dbc_cmd->add_option("device", dbc.target, "device name, or a scene file (its device)")->required();
  dbc_cmd->add_option("--out", dbc.out, "file to write (default: standard output)");

  gyrostab::tools::MotionRecordRequest record;
  CLI::App* record_cmd = app.add_subcommand(
      "motion-record", "write the base motion a scene's generator produces as a motion record (CSV) that "
                       "[motion] kind = \"recorded\" replays");
  record_cmd->add_option("scene", record.scene_path, "scene file (TOML)")->required();
  record_cmd->add_option("--out", record.out_path, "CSV file to write")->required();
  record_cmd->add_option("--step-s", record.step_s, "sample interval [s] (default 0.01)");
  record_cmd->add_option("--duration-s", record.duration_s,
                         "span recorded [s] (default: the scene's duration_s; longer lets --ticks run past it)");

  // The live view of a running bus, heard by a passive listener (docs/view.md).
  gyrostab::tools::view::LcmViewRequest lcm_view;
  lcm_view.url = gyrostab::hil::kDefaultLcmUrl;
  CLI::App* view_cmd = app.add_subcommand(
      "view", "serve a live view of a running plant/controller bus, heard by a listener that never sends "
              "(frames, their signals, status and safe state; docs/view.md)");
  view_cmd->add_option("--lcm-url", lcm_view.url, "the bus (udpm://GROUP:PORT, LCM's form)");
  view_cmd->add_option("--key-file", lcm_view.key_file,
                       "the link's key: show only frames whose MAC verifies (without it, frames are shown marked "
                       "as not authenticated)")
      ->check(CLI::ExistingFile);
  CLI::Option* view_suffix = view_cmd->add_option(
      "--channel-suffix", lcm_view.channel_suffix,
      "listen to GYROSTAB_SENSOR<S> and GYROSTAB_ACTUATOR<S> (default: the suffix of the first frame heard)");
  view_cmd->add_option("--scene", lcm_view.scene_path,
                       "the scene that runs on the bus: its device, length, tick and limits (default: the device "
                       "from the first frame's type)")
      ->check(CLI::ExistingFile);
  view_cmd->add_option("--ticks", lcm_view.ticks, "with --scene: the run's length in ticks")
      ->check(CLI::NonNegativeNumber);
  view_cmd->add_option("--view", lcm_view.view_address,
                       "serve at ADDR:PORT (default 127.0.0.1 on a free port; the URL with its token is printed)");
  view_cmd->add_option("--idle-exit", lcm_view.idle_exit_s,
                       "exit once frames came and none for this long [s] (default: run until Ctrl-C)");

  // MCAP from a bus log (docs/mcap.md).
  gyrostab::tools::ExportRequest export_req;
  CLI::App* export_cmd = app.add_subcommand(
      "export", "write a bus log (gyrostab run --log) or a candump log (--can-log) as an MCAP file for Foxglove, Lichtblick, PlotJuggler "
                "(exit 0 complete, 5 the log is cut or damaged: what it held before is written; docs/mcap.md)");
  export_cmd->add_option("log", export_req.log_path, "bus log (gyrostab run --log) or candump log (--can-log)")->required()->check(CLI::ExistingFile);
  export_cmd->add_option("--mcap", export_req.mcap_path, "the MCAP file to write")->required();
  export_cmd->add_option("--every", export_req.every, "the frames of every N-th tick (default 1: every tick)")
      ->check(CLI::PositiveNumber);

  CLI::App* keys_cmd =
      app.add_subcommand("scene-keys", "print docs/scenes.md: every scene key of every device, from the field tables");

  if (refuse_unknown_subcommand(app, argc, argv)) return 2;
  CLI11_PARSE(app, argc, argv);
  run.view.enabled = run_view->count() > 0;
  plant.view.enabled = plant_view->count() > 0;
  sweep.view = sweep_view->count() > 0;
  if (record_cmd->parsed()) return gyrostab::tools::motion_record(record);
  if (view_cmd->parsed()) {
    lcm_view.suffix_given = view_suffix->count() > 0;
    return gyrostab::tools::view::run_lcm_view(lcm_view);
  }
  if (export_cmd->parsed()) return gyrostab::tools::export_log(export_req);
  if (keys_cmd->parsed()) {
    std::fputs(gyrostab::tools::scenes_markdown().c_str(), stdout);
    return 0;
  }
  if (dbc_cmd->parsed()) return gyrostab::tools::write_dbc(dbc);
  if (accuracy_cmd->parsed()) return gyrostab::tools::run_accuracy(accuracy);
  if (merge_cmd->parsed()) return gyrostab::tools::sweep::merge_study_dir(merge_dir, sweep.quiet);
  if (sweep_cmd->parsed()) {
    if (sweep.study_path.empty()) {
      std::fprintf(stderr, "gyrostab sweep: a study file is required (gyrostab sweep STUDY.toml --out DIR)\n");
      return 2;
    }
    return gyrostab::tools::sweep::run_sweep(sweep);
  }
  if (replay_cmd->parsed()) {
    if (resimulate) replay.role = gyrostab::tools::Role::kResimulate;
    if (replay_target && resimulate) {
      std::fprintf(stderr, "gyrostab replay: --target replays into the controller; --resimulate has no controller\n");
      return 2;
    }
    if (replay_target) replay.transport.transport = "target";
    replay.write_outputs = resimulate && replay_out->count() > 0;
    return gyrostab::tools::replay_log(replay);
  }
  if (demo_cmd->parsed()) return gyrostab::tools::run_demo(demo);
  if (run_cmd->parsed() && run.transport.transport == "lcm" && !run.transport.can_if.empty()) {
    std::fprintf(stderr, "gyrostab run: --can-if needs --transport can\n");
    return 2;
  }
  if (run_cmd->parsed() && run.transport.transport == "can" && run.transport.can_if.empty()) {
    run.transport.can_if = "vcan0";  // CAN FD over SocketCAN, docs/can.md
  }
  if (run_cmd->parsed() && (run.transport.transport == "lcm" || run.transport.transport == "can")) {
    return gyrostab::tools::run_process_pair(run);
  }
  if (run_cmd->parsed()) {
    const gyrostab::tools::TransportOptions& t = run.transport;
    const bool target_options = !t.target_image.empty() || t.target_link != "fifo" || t.target_core != "m7" ||
                                t.qemu != gyrostab::tools::TransportOptions{}.qemu || t.target_faults.any();
    if (t.transport != "target" && target_options) {
      std::fprintf(stderr, "gyrostab run: --target-image, --target-link, --target-core, --qemu and --target-fault need --transport target\n");
      return 2;
    }
    if (t.transport == "target") {
      // The plant runs here; the controller is the image on the emulated target (tools/run/plant_process.cpp).
      run.role = gyrostab::tools::Role::kPlant;
      return gyrostab::tools::run_scene(run);
    }
  }
  if (run_cmd->parsed()) {
    if (const std::string bad = gyrostab::tools::check_inproc_options(run); !bad.empty()) {
      std::fprintf(stderr, "gyrostab run: %s\n", bad.c_str());
      return 2;
    }
  }
  if (plant_cmd->parsed()) return gyrostab::tools::run_scene(plant);
  if (controller_cmd->parsed()) return gyrostab::tools::run_scene(controller);
  if (run_cmd->parsed()) return gyrostab::tools::run_scene(run);
  if (check_cmd->parsed()) return gyrostab::tools::run_scene(check);
  return 0;
}
