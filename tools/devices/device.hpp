// A device, as the run modes and the registry see it: its descriptor (name, scene schema, CAN nodes, the
// accuracy study if it takes the device) and the scene it reads, which builds the plant and the controller
// separately — the plant process builds no controller, the controller process and replay no plant.
// Adding a device: docs/adding-a-device.md. The list of devices: tools/devices/registry.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hil/link/actuator_frame_check.hpp"
#include "sim/motion/scene_base_motion.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/loop/plant_port.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_doc.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

struct AccuracyRequest;

// What the plant is built for.
struct PlantOptions {
  // The whole loop runs in this process (`gyrostab run` in process): a scene that compares a reduced model
  // with its full model runs the full model first. Other modes build the plant alone.
  bool in_process{true};
  std::int64_t ticks{-1};  // the run's length when --ticks set it (< 0: the scene's duration)
};

// A device's scene, read and checked (every start-up check of the plant and of the controller passed).
class DeviceScene {
 public:
  virtual ~DeviceScene() = default;

  virtual const LoopConfig& loop() const = 0;
  // The CSV columns this scene records ([output] signals picks from them).
  virtual std::vector<std::string> columns() const = 0;
  // The columns of the row the plant writes (PlantPort::record), in order: columns() plus those of the
  // device's table that this scene does not have (a column `when` an option the scene does not take).
  virtual std::vector<std::string> row_columns() const { return columns(); }
  // The command limits a drive of this scene accepts (the plant side's check of every received frame).
  virtual hil::ActuatorLimits actuator_limits() const { return hil::ActuatorLimits{}; }
  // report.json "limits": the scene's physical limits in SI units, for the plot (tools/plot/LIMITS.md).
  virtual nlohmann::json limits() const { return nlohmann::json::object(); }

  // The plant may keep references into this scene: the scene outlives it.
  virtual std::unique_ptr<PlantPort> make_plant(const PlantOptions& options) const = 0;
  virtual std::unique_ptr<ControllerPort> make_controller() const = 0;
  // The controller's configuration as the bytes of its Config struct: what `run --transport target` sends to
  // the device's firmware image (firmware/target/pil_session.hpp). Empty: the device has no firmware image.
  virtual std::vector<std::uint8_t> controller_config() const { return {}; }
  // The base motion of a device whose base moves (sim/motion/scene_base_motion.hpp), for
  // `gyrostab motion-record`; nullptr: the device has none.
  virtual const motion::SceneBaseMotion* base_motion() const { return nullptr; }
};

// The bytes of a trivially copyable configuration struct (DeviceScene::controller_config).
template <class Config>
std::vector<std::uint8_t> config_bytes(const Config& c) {
  static_assert(std::is_trivially_copyable_v<Config>, "a configuration travels to the target as its bytes");
  const auto* p = reinterpret_cast<const std::uint8_t*>(&c);
  return std::vector<std::uint8_t>(p, p + sizeof(Config));
}

struct DeviceDescriptor {
  std::string_view name;     // [scene] device
  std::string_view summary;  // one paragraph for docs/scenes.md: what it models, the book's section
  std::string_view figures;  // docs/scenes.md: what report.json's "figures" (and the device's own blocks) hold
  // Reads and checks a scene (the reader holds every problem); nullptr when refused.
  std::unique_ptr<DeviceScene> (*read)(SceneReader& reader);
  // The scene keys, for docs/scenes.md (generated: tools/scene/scene_doc.hpp).
  SceneDoc (*doc)();
  // `gyrostab accuracy` on a scene of this device; nullptr: the study does not take it.
  int (*accuracy)(SceneReader& reader, const AccuracyRequest& request){nullptr};
};

}  // namespace gyrostab::tools
