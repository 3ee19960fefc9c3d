// The ship roll damper in the registry (tools/devices/registry.cpp).
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_study.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kShipRollDamper{
    .name = "ship_roll_damper",
    .summary =
        "The gyroscopic ship roll damper of Magnus §14.2, (14.8), with large-angle terms and precession end stops "
        "(sim/plants/ship_roll_damper_plant.hpp, docs/models/ship-roll-damper.md), in a regular or irregular beam "
        "sea, under the firmware's passive precession brake or active precession control. The same ship with the "
        "gyro locked runs in the same sea as the unstabilized reference. Shipped: "
        "`sim/scenes/ship-roll-damper-passive.toml`, `sim/scenes/ship-roll-damper-active.toml`. Integrator: "
        "`rk4` (the only one).",
    .read = read_ship_roll_damper,
    .doc = ship_roll_damper_doc,
    .can_nodes = can::kNodeImu | can::kNodeDrive2,  // roll sensor; one precession axis (2)
    .accuracy = ship_roll_damper_accuracy,
};

}  // namespace gyrostab::tools
