// `gyrostab run SCENE --transport target` before its loop (docs/pil.md): finds the device's controller image,
// starts it on the emulated Cortex-M7 and binds the session (hil/target/target_endpoint.hpp), sending the
// scene's controller configuration; the image's start-up check answers as the host's would. The plant loop
// then runs over the link unchanged (plant_process.cpp). Nothing is built at run time: the images come from the
// build (tools/setup, firmware/CMakeLists.txt: build/arm/m7/<device>.elf).
// Returns 0, or the exit code with the message printed: 2 refused (no image for the device, options that do
// not apply, the configuration refused by the image), 6 the image never booted or never answered.
#pragma once

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "hil/target/target_endpoint.hpp"
#include "tools/build_paths.hpp"
#include "tools/devices/device.hpp"
#include "tools/devices/registry.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/run/link_settings.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// The image of a device: --target-image, else $GYROSTAB_IMAGE_DIR/<core>/<device>.elf (core m7 or m4), else the
// build's (build/arm/<core>/).
inline std::string target_image_path(const std::string& device, const TransportOptions& t) {
  if (!t.target_image.empty()) return t.target_image;
  const char* env = std::getenv("GYROSTAB_IMAGE_DIR");
  const std::string dir = env != nullptr && *env != '\0' ? env : build_image_dir();
  return dir + (t.target_core == "m4f" ? "/m4/" : "/m7/") + device + ".elf";
}

inline int open_target_link(const DeviceScene& scene, RunRequest& req, hil::TargetBus& bus, nlohmann::json& info) {
  TransportOptions& t = req.transport;
  const LoopConfig& loop = scene.loop();
  const std::vector<std::uint8_t> config = scene.controller_config();
  if (config.empty()) {
    std::fprintf(stderr, "gyrostab run: %s: the %s device has no firmware controller image\n", loop.name.c_str(),
                 loop.device.c_str());
    return 2;
  }
  if (t.real_time) {
    std::fprintf(stderr, "gyrostab run: --transport target runs in lockstep (-icount); --real-time does not apply\n");
    return 2;
  }
  if (!t.key_file.empty()) {
    std::fprintf(stderr,
                 "gyrostab run: --key-file with --transport target: the images hold no link key (a key would be "
                 "provisioned into the target's flash, not sent over the link); the session binding applies\n");
    return 2;
  }
  const std::string image = target_image_path(loop.device, t);
  struct stat st{};
  if (stat(image.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    std::fprintf(stderr,
                 "gyrostab run: no controller image for %s at %s (tools/setup builds the images when "
                 "arm-none-eabi-g++ is installed; or --target-image PATH)\n",
                 loop.device.c_str(), image.c_str());
    return 2;
  }
  LinkIdentity id;
  if (std::string error; !link_identity(t, /*plant_side=*/true, id, error)) {
    std::fprintf(stderr, "gyrostab run: %s\n", error.c_str());
    return 2;
  }
  t.session = id.session;  // the plant loop's guard takes the same session
  bus.launch.qemu = t.qemu;
  bus.launch.image = image;
  bus.launch.device = loop.device;
  bus.set_device(signals_of(scene));
  bus.launch.uart = t.target_link == "uart";
  if (t.target_core == "m4f") {
    bus.launch.machine = "mps2-an386";
    bus.launch.cpu = "cortex-m4";
  }
  bus.faults = t.target_faults;
  const LinkSettings s = link_settings(loop, t);
  bus.write_timeout_ns = s.timeout_ns;
  const std::string error = open_target_session(bus, static_cast<std::uint32_t>(id.session),
                                                static_cast<std::uint32_t>(id.own_id), config,
                                                hil::monotonic_ns() + s.start_timeout_ns);
  if (!error.empty()) {
    std::fprintf(stderr, "gyrostab run: %s: target: %s\n", loop.name.c_str(), error.c_str());
    bus.qemu.close();
    return bus.hello.config_bytes != 0 ? 2 : kExitPeerLost;
  }
  if (bus.verdict.accepted == 0) {
    firmware::ConfigCheck c = firmware::ConfigCheck::refused(bus.verdict.reason, bus.verdict.value,
                                                             bus.verdict.lower, bus.verdict.upper);
    std::fprintf(stderr, "gyrostab run: %s: refused by the controller's start-up check on the target: %s\n",
                 loop.name.c_str(), describe(c).c_str());
    bus.qemu.close();
    return 2;
  }
  info = {{"transport", "target"},
          {"image", image},
          {"channel", bus.launch.uart ? "uart" : "fifo"},
          {"core", t.target_core},
          {"timeout_ms", t.timeout_ms},
          {"start_timeout_ms", t.start_timeout_ms}};
  return 0;
}

}  // namespace gyrostab::tools
