// The DBC file of the bus (Vector CANdb++ text format), written from the frame map (frame_map.hpp) so that
// common CAN tools (cantools, canmatrix, SavvyCAN, CANalyzer, candump | cantools decode) decode a recorded
// bus. `gyrostab dbc` prints it; tests/unit/can_dbc_test.cpp parses it back and compares it with the map, and
// checks it with an independent DBC reader (python3-canmatrix) decoding frames of the encoder.
//
// What the file states: every message (id, FD length, sender node, VFrameFormat = StandardCAN_FD, bit-rate
// switch), every signal (Intel byte order, start bit, length, signedness, factor, offset, range, unit,
// receivers, comment), IEEE-754 double signals as SIG_VALTYPE_ 2, and the bus type "CAN FD".
// Not on a hot path: builds a std::string.
#pragma once

#include <string>

namespace gyrostab::can {

std::string dbc_text();

}  // namespace gyrostab::can
