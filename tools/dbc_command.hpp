// `gyrostab dbc DEVICE|SCENE [--out FILE]`: the DBC file of a device's CAN FD bus (hil/can/dbc_writer.hpp) —
// the map generated from its signal table, every frame of it. DEVICE is a [scene] device name; a scene file
// names its device.
#pragma once

#include <string>

namespace gyrostab::tools {

struct DbcRequest {
  std::string target;  // a device name or a scene file
  std::string out;     // "": standard output
};

// Exit code: 0 written, 2 unknown device or refused scene, 3 the file could not be written.
int write_dbc(const DbcRequest& req);

}  // namespace gyrostab::tools
