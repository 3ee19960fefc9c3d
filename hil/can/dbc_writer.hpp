// The DBC file of a device's bus (Vector CANdb++ text format), written from its map (frame_map.hpp DeviceBus:
// the frames its signal table generates, gyrostab_signals/<device>_can.hpp) so that common CAN tools (cantools,
// canmatrix, SavvyCAN, CANalyzer, candump | cantools decode) decode a recorded bus. `gyrostab dbc DEVICE|SCENE`
// prints it; tests/unit/can_dbc_test.cpp parses it back and compares it with every map, and checks it with an
// independent DBC reader (python3-canmatrix) decoding frames of the encoder.
//
// What the file states: the bus's nodes, every message on the bus (id, FD length, sender node,
// VFrameFormat = StandardCAN_FD, bit-rate switch), every signal (Intel byte order, start bit, length,
// signedness, factor, offset, range, unit, receivers, comment), IEEE-754 double signals as SIG_VALTYPE_ 2, and
// the bus type "CAN FD". Not on a hot path: builds a std::string.
#pragma once

#include <string>

#include "hil/can/frame_map.hpp"

namespace gyrostab::can {

std::string dbc_text(const DeviceBus& bus);

}  // namespace gyrostab::can
