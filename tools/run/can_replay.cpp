#include "tools/run/can_replay.hpp"

#include "hil/can/link_seal.hpp"
#include "hil/link/end_of_run.hpp"
#include "tools/devices/registry.hpp"

namespace gyrostab::tools {

int replay_controller_candump(ControllerPort& controller, const LoopConfig& loop, const msg::DeviceSignals& signals,
                              const RunRequest& req) {
  const std::string& path = req.transport.replay_log;
  can::CandumpFile file;
  std::string error;
  if (!can::read_candump_file(path, file, error)) {
    std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
    return kReplayExitBadLog;
  }
  // A gyrostab log names its run in its header: it must agree with the scene (unless --scene overrides).
  std::string differs;
  const auto check = [&](const char* key, const std::string& want) {
    const std::string got = candump_header(file, key);
    if (!got.empty() && got != want) differs += std::string(" ") + key + " '" + got + "' vs '" + want + "';";
  };
  check("scene", loop.name);
  check("device", loop.device);
  check("seed", std::to_string(loop.seed));
  check("tick_ns", std::to_string(loop.tick_ns));
  if (!differs.empty()) {
    if (!req.transport.replay_scene_override) {
      std::fprintf(stderr, "gyrostab: %s: the log's header disagrees with its scene:%s\n", path.c_str(),
                   differs.c_str());
      return kReplayExitBadLog;
    }
    std::fprintf(stderr, "gyrostab: %s: note: --scene differs from the recorded scene:%s\n", path.c_str(),
                 differs.c_str());
  }
  // The frames are decoded with the map of the scene's device: the one the log was recorded with, or the log is
  // refused (its identifiers and positions would mean something else).
  const can::CanMap* found = find_device_can_map(loop.device);
  if (found == nullptr) {
    std::fprintf(stderr, "gyrostab: %s: device %s has no signal table in this build, so no CAN map\n", path.c_str(),
                 loop.device.c_str());
    return kReplayExitBadLog;
  }
  const can::CanMap& map = *found;
  const std::string version = candump_header(file, "gyrostab-candump");
  if (!version.empty() && version != "2") {
    std::fprintf(stderr, "gyrostab: %s: a gyrostab candump log of version %s, recorded with another CAN map "
                 "(this build writes and replays version 2, its maps generated from the signal tables): record "
                 "it again\n", path.c_str(), version.c_str());
    return kReplayExitBadLog;
  }
  if (const std::string recorded = candump_header(file, "can-map");
      !recorded.empty() && recorded != can_map_text(map)) {
    std::fprintf(stderr, "gyrostab: %s: recorded with the CAN map '%s', but device %s's map in this build is "
                 "'%s' (table and fingerprint): its frames would be decoded wrongly; record it again\n",
                 path.c_str(), recorded.c_str(), loop.device.c_str(), can_map_text(map).c_str());
    return kReplayExitBadLog;
  }
  const can::DeviceBus bus = can::whole_bus(map);
  if (map.signals->device != signals.device) {
    std::fprintf(stderr, "gyrostab: %s: device %s's CAN map carries the frames of table %s, not %s\n", path.c_str(),
                 loop.device.c_str(), std::string(map.signals->device).c_str(), std::string(signals.device).c_str());
    return kReplayExitBadLog;
  }

  can::SetAssembler sensors(bus, can::Direction::kSensor);
  can::SetAssembler commands(bus, can::Direction::kActuator);
  can::FrameEncoder encoder(bus, can::Direction::kActuator);
  std::deque<can::CanFrame> due;  // the controller's frames not yet matched against the log
  std::array<can::CanFrame, can::kMaxMessagesPerDirection> tx{};
  msg::AnySensorFrame sensor{};
  msg::AnyActuatorFrame out{}, recorded{};
  std::int64_t last_tick = -1;
  bool ended = false;  // the plant's end-of-run set was seen (docs/protocol.md)
  std::int64_t ticks = 0, compared = 0, skipped = 0;
  timespec pace{};
  clock_gettime(CLOCK_MONOTONIC, &pace);
  const auto push_encoded = [&](const msg::AnyActuatorFrame& a) {
    const std::size_t n = encoder.encode(a, tx);
    for (std::size_t i = 0; i < n; ++i) due.push_back(tx[i]);
    return n > 0;
  };
  const auto sensor_id = [&](std::uint32_t id) {
    const int i = bus.index_of(id);
    return i >= 0 && bus.messages()[static_cast<std::size_t>(i)].direction == can::Direction::kSensor;
  };
  for (const can::CandumpRecord& r : file.frames) {
    const can::CanFrame& f = r.frame;
    const bool command_id = !(f.flags & (can::kFlagError | can::kFlagExtended)) && bus.index_of(f.id) >= 0 &&
                            !sensor_id(f.id);
    if (!command_id) {
      if (sensors.accept(f) != can::FrameError::kNone) {
        ++skipped;
        continue;
      }
      if (!sensors.ready()) continue;
      sensors.take(sensor);
      const auto k = static_cast<std::int64_t>(sensor.tick);
      if (k == last_tick) continue;  // the plant sent this tick again: the controller answers from its cache
      if (!due.empty()) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH: the sensor set of tick %lld arrives while the controller's "
                     "%s for tick %lld is missing from the log\n", path.c_str(), r.line, static_cast<long long>(k),
                     describe_can_frame(due.front()).c_str(), static_cast<long long>(last_tick));
        return kReplayExitMismatch;
      }
      if (hil::is_end_of_run(sensor)) {
        // The plant's end of the run: the controller does not step on it; it acknowledges it.
        push_encoded(hil::end_of_run_ack(sensor, out, controller.monitor_status(), loop.tick_ns, signals));
        last_tick = k;
        ended = true;
        continue;
      }
      if (ended) {
        std::fprintf(stderr, "gyrostab: %s:%d: a sensor set of tick %lld after the plant's end of the run\n",
                     path.c_str(), r.line, static_cast<long long>(k));
        return kReplayExitBadLog;
      }
      if (req.transport.replay_real_time) {
        const std::int64_t ns = static_cast<std::int64_t>(pace.tv_nsec) + loop.tick_ns;
        pace.tv_sec += static_cast<time_t>(ns / 1'000'000'000);
        pace.tv_nsec = static_cast<long>(ns % 1'000'000'000);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &pace, nullptr) == EINTR) {
        }
      }
      controller.step(static_cast<std::uint64_t>(k), &sensor, out);
      last_tick = k;
      ++ticks;
      if (!push_encoded(out)) {
        std::fprintf(stderr, "gyrostab: %s: the controller's command for tick %lld has a value the device's CAN "
                     "bus cannot carry exactly\n", path.c_str(), static_cast<long long>(k));
        return kReplayExitMismatch;
      }
      continue;
    }
    // A frame on a command identifier: the controller's.
    const can::FrameError e = commands.accept(f);
    if (e != can::FrameError::kNone) {
      if (!due.empty() && due.front().id == f.id) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH at tick %lld: the recorded frame is rejected (%s) where the "
                     "controller sends %s\n", path.c_str(), r.line, static_cast<long long>(last_tick),
                     std::string(can::frame_error_name(e)).c_str(), describe_can_frame(due.front()).c_str());
        return kReplayExitMismatch;
      }
      ++skipped;
      continue;
    }
    if (due.empty()) {
      // A command set recorded again for the tick just stepped: the controller's resend, re-encoded.
      if (last_tick < 0 || !push_encoded(out)) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH: a command frame before any sensor set: %s\n", path.c_str(),
                     r.line, describe_can_frame(f).c_str());
        return kReplayExitMismatch;
      }
    }
    can::CanFrame want = due.front();
    due.pop_front();
    // The header's link envelope (sender, session, freshness, MAC) is the recorded run's, drawn at its start,
    // not something the controller computes from the log: taken from the recorded frame. Everything else,
    // the CRC over it included, must match bit for bit.
    if (const int i = bus.index_of(want.id); i >= 0 && bus.messages()[static_cast<std::size_t>(i)].header &&
                                             f.len == want.len) {
      can::write_link_envelope(want, can::read_link_envelope(f));
    }
    const bool same = want.id == f.id && want.len == f.len &&
                      (want.flags & (can::kFlagFd | can::kFlagBrs | can::kFlagEsi)) ==
                          (f.flags & (can::kFlagFd | can::kFlagBrs | can::kFlagEsi)) &&
                      std::memcmp(want.data, f.data, f.len) == 0;
    if (!same) {
      std::string fields;
      if (commands.ready() && commands.take(recorded)) fields = "; fields: " + buslog::frame_differences(recorded, out, signals);
      std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH at tick %lld (%lld frames before it identical): recorded %s, "
                   "controller %s%s\n", path.c_str(), r.line, static_cast<long long>(last_tick),
                   static_cast<long long>(compared), describe_can_frame(f).c_str(), describe_can_frame(want).c_str(),
                   fields.c_str());
      return kReplayExitMismatch;
    }
    ++compared;
    if (commands.ready()) commands.take(recorded);
  }
  if (ticks == 0) {
    std::fprintf(stderr, "gyrostab: %s: no complete sensor set in the log, nothing replayed\n", path.c_str());
    return 2;
  }
  if (!due.empty()) {
    std::fprintf(stderr, "gyrostab: %s: the log ends before the controller's %s for tick %lld; the %lld frames "
                 "before it are identical\n", path.c_str(), describe_can_frame(due.front()).c_str(),
                 static_cast<long long>(last_tick), static_cast<long long>(compared));
    return kReplayExitBadLog;
  }
  std::printf("%s: %lld ticks, every CAN frame of the controller identical (%lld frames, bit for bit); %lld recorded "
              "frames rejected by the decoder and skipped, as the controller skipped them\n",
              path.c_str(), static_cast<long long>(ticks), static_cast<long long>(compared),
              static_cast<long long>(skipped));
  return 0;
}

}  // namespace gyrostab::tools
