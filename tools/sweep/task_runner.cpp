#include "tools/sweep/task_runner.hpp"

#include <chrono>

#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/loop/state_guard.hpp"
#include "tools/sweep/task_record.hpp"

namespace gyrostab::tools::sweep {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

nlohmann::json kept_figures(const nlohmann::json& all) {
  nlohmann::json out = nlohmann::json::object();
  for (std::string_view name : kTaskFigures) {
    const auto it = all.find(std::string(name));
    out[std::string(name)] = (it != all.end() && it->is_number()) ? *it : nlohmann::json();
  }
  return out;
}

}  // namespace

nlohmann::json run_task(const Study& s, const Task& t) {
  const Clock::time_point start = Clock::now();
  const std::string text = task_scene_text(s, t);
  nlohmann::json record{{"format", kTaskFormat},
                        {"task", task_block(s, t)},
                        {"definition_hash", definition_hash(s, t, text)},
                        {"scene", text},
                        {"reasons", nlohmann::json::array()}};
  nlohmann::json figures = kept_figures(nlohmann::json::object());
  double setup_s = 0.0, run_s = 0.0;

  SceneReader reader;
  std::unique_ptr<DeviceScene> scene;
  if (reader.parse(text, t.label(s))) scene = read_device_scene(reader);
  if (scene == nullptr) {
    record["outcome"] = kRefused;
    for (const std::string& e : reader.errors()) record["reasons"].push_back(e);
    if (reader.errors().empty()) record["reasons"].push_back(t.label(s) + ": the scene was refused");
    setup_s = seconds_since(start);
  } else {
    std::unique_ptr<PlantPort> plant = scene->make_plant(PlantOptions{true, -1});
    std::unique_ptr<ControllerPort> controller = scene->make_controller();
    setup_s = seconds_since(start);
    const Clock::time_point loop_start = Clock::now();
    const LoopOutcome outcome = run_closed_loop(*plant, *controller, scene->loop(), nullptr, false, nullptr);
    run_s = seconds_since(loop_start);
    figures = kept_figures(plant->figures());
    if (outcome.diverged) {
      record["outcome"] = kDiverged;
      record["reasons"].push_back(describe_non_finite(t.label(s), outcome.diverged_tick, outcome.diverged_state));
    } else {
      record["outcome"] = kCompleted;
    }
  }
  record["figures"] = figures;
  record["result_check"] = result_check(record);
  record["timing"] = {{"setup_s", setup_s}, {"run_s", run_s}};
  return record;
}

}  // namespace gyrostab::tools::sweep
