// gyrostab — command-line entry point: demo, run, check.
#include <CLI/CLI.hpp>

#include "tools/commands.hpp"
#include "tools/demo_gimbal_gyro.hpp"

int main(int argc, char** argv) {
  CLI::App app{"gyrostab: gyroscopic stabilizers and gimbal drives"};
  app.require_subcommand(1);

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

  gyrostab::tools::RunRequest check;
  check.check_only = true;
  CLI::App* check_cmd = app.add_subcommand("check", "validate a scene without running it");
  check_cmd->add_option("scene", check.scene_path, "scene file (TOML)")->required();

  CLI11_PARSE(app, argc, argv);
  if (demo_cmd->parsed()) return gyrostab::tools::run_demo(demo);
  if (run_cmd->parsed()) return gyrostab::tools::run_scene(run);
  if (check_cmd->parsed()) return gyrostab::tools::run_scene(check);
  return 0;
}
