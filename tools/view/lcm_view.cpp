#include "tools/view/lcm_view.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include "tools/commands.hpp"
#include "tools/devices/registry.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/run/run_output.hpp"
#include "tools/scene/scene_reader.hpp"
#include "tools/view/lcm_listener.hpp"
#include "tools/view/run_view.hpp"
#include "tools/view/view_server.hpp"

namespace gyrostab::tools::view {

namespace {

bool stop_requested() { return stop_signal_received() != 0; }

ViewChannel frame_view_channel(const msg::DeviceSignals& device, FrameDirection d, LiveRing& ring) {
  ViewChannel c;
  c.info = frame_channel(device, d);
  SignalInfo t;
  t.name = "t_s";
  t.unit = "s";
  t.symbol = "t";
  t.description = "the frame's time (time_ns)";
  t.declared = true;
  c.info.signals.insert(c.info.signals.begin(), t);
  c.ring = &ring;
  c.status = d == FrameDirection::kActuator ? "fault" : "sensor";
  return c;
}

}  // namespace

int run_lcm_view(const LcmViewRequest& req) {
  ListenerOptions o;
  o.url = req.url;
  o.channel_suffix = req.channel_suffix;
  o.suffix_given = req.suffix_given;
  ViewOptions vo;
  if (const std::string bad = parse_view_address(req.view_address, vo); !bad.empty()) {
    std::fprintf(stderr, "gyrostab view: --view %s\n", bad.c_str());
    return 2;
  }
  if (UdpmAddress a; !parse_udpm_url(req.url, a).empty()) {
    std::fprintf(stderr, "gyrostab view: %s\n", parse_udpm_url(req.url, a).c_str());
    return 2;
  }
  if (!req.key_file.empty()) {
    firmware::link::Key128 key;
    std::string error;
    if (!read_key_file(req.key_file, key, error)) {
      std::fprintf(stderr, "gyrostab view: %s\n", error.c_str());
      return 2;
    }
    o.key = key;
  }
  // The scene, if given: the device, the run's length, tick and limits.
  std::unique_ptr<DeviceScene> scene;
  nlohmann::json scene_json, limits = nlohmann::json::object();
  std::int64_t total_ticks = 0, tick_ns = 0;
  int every = 1;
  if (!req.scene_path.empty()) {
    SceneReader reader;
    if (reader.open(req.scene_path)) scene = read_device_scene(reader);
    for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
    if (scene == nullptr) {
      std::fprintf(stderr, "gyrostab view: --scene %s refused\n", req.scene_path.c_str());
      return 2;
    }
    const LoopConfig& loop = scene->loop();
    o.device = &signals_of(*scene);
    scene_json = scene_summary(loop, req.scene_path);
    if (req.ticks >= 0) scene_json["duration_s"] = static_cast<double>(req.ticks) * loop.tick_s();
    limits = scene->limits();
    total_ticks = req.ticks >= 0 ? req.ticks : loop.ticks();
    tick_ns = loop.tick_ns;
  }
  LcmListener listener;
  std::string error;
  if (!listener.open(o, error)) {
    std::fprintf(stderr, "gyrostab view: %s\n", error.c_str());
    return 3;
  }
  StopSignalGuard guard;
  const msg::DeviceSignals* device = o.device;
  if (device == nullptr || tick_ns == 0) {
    std::fprintf(stderr, "gyrostab view: listening on %s; the first frames tell the device and the tick%s\n",
                 req.url.c_str(), device == nullptr ? " (or name the scene: --scene)" : "");
    std::fflush(stderr);
    std::int64_t learnt_tick_ns = 0;
    device = listener.learn(&stop_requested, learnt_tick_ns);
    if (device == nullptr) return 0;  // stopped before any frame
    if (tick_ns == 0) tick_ns = learnt_tick_ns;
  }
  if (scene_json.is_null()) {
    scene_json = {{"name", "LCM bus " + req.url}, {"device", std::string(device->device)}, {"tick_ns", tick_ns}};
  }
  LiveRing sensor(1 + frame_width(*device, FrameDirection::kSensor), kRingRows);
  LiveRing actuator(1 + frame_width(*device, FrameDirection::kActuator), kRingRows);
  ViewRun run;
  run.source = "lcm";
  run.scene = scene_json;
  run.channels.push_back(frame_view_channel(*device, FrameDirection::kSensor, sensor));
  run.channels.push_back(frame_view_channel(*device, FrameDirection::kActuator, actuator));
  run.limits = limits;
  run.total_ticks = total_ticks;
  run.record_every = every;
  run.tick_s = static_cast<double>(tick_ns) * 1e-9;
  run.growable = true;
  run.link = [&listener] { return listener.link_json(); };
  ViewServer server;
  if (!server.start(vo, run, error)) {
    std::fprintf(stderr, "gyrostab view: %s\n", error.c_str());
    return 3;
  }
  listener.start(sensor, actuator);
  std::fprintf(stderr, "gyrostab: live view of the bus %s (device %s) at %s\n", req.url.c_str(),
               std::string(device->device).c_str(), server.url().c_str());
  std::fflush(stderr);
  std::uint64_t last_count = 0;
  auto last_change = std::chrono::steady_clock::now();
  while (stop_signal_received() == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (req.idle_exit_s > 0) {
      const std::uint64_t n = listener.sensor_counts().received + listener.actuator_counts().received;
      const auto now = std::chrono::steady_clock::now();
      if (n != last_count) {
        last_count = n;
        last_change = now;
      } else if (n > 0 && std::chrono::duration<double>(now - last_change).count() > req.idle_exit_s) {
        break;
      }
    }
  }
  listener.stop();
  server.stop();
  const nlohmann::json summary = listener.summary_json();
  std::printf("%s\n", summary.dump().c_str());
  std::fprintf(stderr, "gyrostab view: heard %llu sensor and %llu actuator frames, showed %llu and %llu\n",
               static_cast<unsigned long long>(listener.sensor_counts().received.load()),
               static_cast<unsigned long long>(listener.actuator_counts().received.load()),
               static_cast<unsigned long long>(listener.sensor_counts().shown.load()),
               static_cast<unsigned long long>(listener.actuator_counts().shown.load()));
  return 0;
}

}  // namespace gyrostab::tools::view
