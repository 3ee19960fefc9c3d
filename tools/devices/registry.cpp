#include "tools/devices/registry.hpp"

#include "tools/signals/device_signals.hpp"

namespace gyrostab::tools {

// The devices, one line each: the descriptor defined in tools/devices/<device>/<device>_device.cpp.
#define GYROSTAB_DEVICES(X) \
  X(kShipRollDamper)        \
  X(kPowerStabilizer)       \
  X(kMonorail)              \
  X(kServoGyro)             \
  X(kGyroVertical)          \
  X(kDirectionalGyro)       \
  X(kGyrocompass)           \
  X(kInertialPlatform)      \
  X(kGyroPendulum)          \
  X(kGimbalError)           \
  X(kUGyro)                 \
  X(kConing)                \
  X(kFoucaultGyro)          \
  X(kPositionGyroPlatform)  \
  X(kCmgCluster)            \
  X(kPlatformAlignment)     \
  X(kBauersfeldCompass)     \
  X(kTwoRotorStabilizer)

#define GYROSTAB_DECLARE(d) extern const DeviceDescriptor d;
#define GYROSTAB_ENTRY(d) &d,
GYROSTAB_DEVICES(GYROSTAB_DECLARE)

namespace {
const DeviceDescriptor* const kDevices[] = {GYROSTAB_DEVICES(GYROSTAB_ENTRY)};
}  // namespace

std::span<const DeviceDescriptor* const> devices() { return kDevices; }

const DeviceDescriptor* find_device(std::string_view name) {
  for (const DeviceDescriptor* d : kDevices) {
    if (d->name == name) return d;
  }
  return nullptr;
}

const msg::DeviceSignals& signals_of(const DeviceScene& scene) {
  return *find_device_signals(scene.loop().device);
}

}  // namespace gyrostab::tools
