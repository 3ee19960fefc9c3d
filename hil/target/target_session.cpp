// The handshake and the close of a target link session (target_endpoint.hpp).
#include <cstring>
#include <string>

#include "hil/target/target_endpoint.hpp"

namespace gyrostab::hil {
namespace {

using firmware::link::TargetFrameKind;
using firmware::link::TargetFrameView;

// Waits for one accepted frame of `kind` until deadline_ns (others are counted as unexpected and skipped).
bool await(TargetBus& bus, TargetFrameKind kind, std::int64_t deadline_ns, TargetFrameView& f) {
  for (;;) {
    if (bus.next(deadline_ns, f, /*dead_is_error=*/true) != RxStatus::kMessage) return false;
    if (f.kind == kind) return true;
  }
}

std::string fixed_text(const char* p, std::size_t n) {
  std::size_t len = 0;
  while (len < n && p[len] != '\0') ++len;
  return std::string(p, len);
}

}  // namespace

std::string open_target_session(TargetBus& bus, std::uint32_t session, std::uint32_t sender,
                                std::span<const std::uint8_t> config, std::int64_t start_deadline_ns) {
  std::string error;
  if (!bus.qemu.start(bus.launch, error)) return error;
  bus.encoder = firmware::link::TargetFrameEncoder(sender, session);
  TargetFrameView f;
  if (!await(bus, TargetFrameKind::kHello, start_deadline_ns, f)) {
    return "the image did not boot: no Hello frame from " + bus.launch.image + " within the start timeout (" +
           bus.peer_state() + "; " + std::to_string(bus.decoder.counters().refused()) + " frames refused)";
  }
  std::memcpy(&bus.hello, f.payload.data(), sizeof bus.hello);
  bus.image_sender = f.sender;
  const std::string image = fixed_text(bus.hello.image, sizeof bus.hello.image);
  if (image != bus.launch.device) {
    return "the image " + bus.launch.image + " runs the " + image + " controller, not " + bus.launch.device;
  }
  if (bus.hello.frame_version != firmware::link::kTargetFrameVersion) {
    return "the image speaks target-link version " + std::to_string(bus.hello.frame_version) + ", this build " +
           std::to_string(firmware::link::kTargetFrameVersion) + " (rebuild the image)";
  }
  if (bus.signals != nullptr && (bus.hello.sensor_signals != bus.signals->sensors.size() ||
                                 bus.hello.command_signals != bus.signals->commands.size())) {
    return "the image's " + image + " frames carry " + std::to_string(bus.hello.sensor_signals) + " sensor and " +
           std::to_string(bus.hello.command_signals) + " command signals, this build's signal table " +
           std::to_string(bus.signals->sensors.size()) + " and " + std::to_string(bus.signals->commands.size()) +
           " (rebuild the image)";
  }
  if (bus.hello.config_bytes != config.size()) {
    return "the image's " + image + " configuration has " + std::to_string(bus.hello.config_bytes) +
           " bytes, this build's " + std::to_string(config.size()) + ": the image is of another version (rebuild it)";
  }
  std::array<std::uint8_t, firmware::link::kMaxConfigBytes> bytes{};
  if (config.size() > bytes.size()) {
    return "the " + image + " configuration has " + std::to_string(config.size()) + " bytes, more than a target frame's " +
           std::to_string(bytes.size());
  }
  std::memcpy(bytes.data(), config.data(), config.size());
  if (bus.faults.bad_config) {
    // Every Config starts with RuntimeConfig, whose first field is the base tick: 0 must be refused.
    std::memset(bytes.data(), 0, sizeof(std::int64_t));
  }
  if (!bus.write(bus.encoder.encode(TargetFrameKind::kConfig, bytes.data(), config.size()))) {
    return "cannot send the configuration to the image (" + bus.peer_state() + ")";
  }
  bus.decoder.bind(session, bus.image_sender);
  if (!await(bus, TargetFrameKind::kConfigVerdict, start_deadline_ns, f)) {
    return "the image did not answer its configuration (" + bus.peer_state() + ")";
  }
  std::memcpy(&bus.verdict, f.payload.data(), sizeof bus.verdict);
  return "";
}

bool finish_target_session(TargetBus& bus, std::int64_t deadline_ns) {
  bool ok = false;
  if (!bus.qemu.exited() && bus.injected.frozen_at < 0 &&
      bus.write(bus.encoder.encode(TargetFrameKind::kStop, nullptr, 0))) {
    TargetFrameView f;
    if (await(bus, TargetFrameKind::kProfile, deadline_ns, f)) {
      std::memcpy(&bus.profile, f.payload.data(), sizeof bus.profile);
      bus.have_profile = true;
      ok = bus.qemu.wait_exit(deadline_ns);
    }
  }
  bus.qemu.close();
  return ok;
}

namespace {

nlohmann::json task_json(const firmware::PerfCounter& c, double tick_s, double ns_per_count) {
  nlohmann::json j{{"runs", c.runs}};
  if (c.runs == 0) return j;
  const auto mean = static_cast<double>(c.total_ns) / static_cast<double>(c.runs);
  j["instructions"] = {{"min", c.min_ns}, {"mean", mean}, {"max", c.max_ns}};
  nlohmann::json frac;
  for (const double mhz : {216.0, 480.0}) {
    const double cycles_per_tick = mhz * 1e6 * tick_s;
    frac[std::to_string(static_cast<int>(mhz)) + "_MHz"] = {{"mean", mean / cycles_per_tick},
                                                            {"max", static_cast<double>(c.max_ns) / cycles_per_tick}};
  }
  j["fraction_of_tick"] = frac;
  j["resolution_instructions"] = ns_per_count;
  return j;
}

nlohmann::json rx_json(const firmware::link::TargetRxCounters& c) {
  return {{"accepted", c.accepted}, {"framing", c.framing}, {"length", c.length},
          {"crc", c.crc},           {"reserved_bits", c.reserved_bits}, {"kind", c.kind},
          {"foreign", c.foreign},   {"repeated", c.repeated}, {"skipped", c.skipped},
          {"overflow", c.overflow}};
}

}  // namespace

nlohmann::json target_timing_json(const TargetBus& bus, std::int64_t tick_ns) {
  if (!bus.have_profile) return {{"profile", nullptr}, {"why", "the image sent no profile (it was lost)"}};
  const firmware::link::TargetProfile& p = bus.profile;
  const double tick_s = static_cast<double>(tick_ns) * 1e-9;
  const double res = p.clock_ns_per_count;
  return {{"what_is_counted",
           "instructions executed on QEMU's " + bus.launch.machine + " under -icount shift=0 (1 instruction = 1 ns "
           "of virtual time), read from SysTick in steps of " +
               std::to_string(p.clock_ns_per_count) +
               "; the fractions assume one instruction per core cycle (QEMU has no DWT cycle counter and no "
               "pipeline model)"},
          {"core", bus.launch.cpu == "cortex-m4"
                       ? "Cortex-M4F, FPv4-SP-D16 (single-precision FPU: double in software), image built -Os"
                       : "Cortex-M7, FPv5-D16 (double-precision FPU), image built -Os"},
          {"base_tick_s", tick_s},
          {"ticks", p.ticks},
          {"step", task_json(p.step, tick_s, res)},
          {"control", task_json(p.control, tick_s, res)},
          {"drive", task_json(p.drive, tick_s, res)},
          {"link", task_json(p.link, tick_s, res)}};
}

nlohmann::json target_link_json(TargetBus& bus) {
  nlohmann::json j{{"image", bus.launch.image},
                   {"channel", bus.launch.uart ? "uart (CMSDK UART0 on a QEMU pipe)" : "semihosting FIFOs"},
                   {"emulator", bus.qemu.command_line()},
                   {"emulator_end", bus.qemu.exited() ? bus.qemu.exit_text() : "running"},
                   {"config_accepted", bus.verdict.accepted != 0},
                   {"host_refused", rx_json(bus.decoder.counters())},
                   {"injected",
                    {{"corrupted", bus.injected.corrupted},
                     {"stale", bus.injected.stale},
                     {"skipped", bus.injected.skipped},
                     {"frozen_at_tick", bus.injected.frozen_at},
                     {"killed_at_tick", bus.injected.killed_at}}}};
  if (bus.have_profile) {
    const firmware::link::TargetProfile& p = bus.profile;
    j["image_refused"] = rx_json(p.rx);
    j["image_ticks"] = {{"stepped", p.ticks},     {"without_frame", p.missing}, {"answered_again", p.republished},
                        {"late", p.late},        {"monitor_status", p.monitor_status}};
  }
  return j;
}

}  // namespace gyrostab::hil
