#include "hil/can/dbc_writer.hpp"

#include <cstdio>
#include <string_view>

#include "hil/can/frame_map.hpp"

namespace gyrostab::can {
namespace {

// Shortest text that reads back as the same double (%.17g round-trips every finite double).
std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string receivers(const MessageSpec& m) {
  if (m.direction == Direction::kSensor) return "controller";
  switch (m.requires_node) {
    case kNodeDrive1: return "drive1";
    case kNodeDrive2: return "drive2";
    case kNodeCluster: return "cluster";
    default: return "drive1,drive2,cluster";
  }
}

// DBC comments are double-quoted strings: no quotes inside.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"') ? '\'' : c;
  return out + "\"";
}

}  // namespace

std::string dbc_text() {
  std::string o;
  o += "VERSION \"gyrostab-can-1\"\n\n\n";
  o += "NS_ :\n\tCM_\n\tBA_DEF_\n\tBA_\n\tBA_DEF_DEF_\n\tSIG_VALTYPE_\n\n";
  o += "BS_:\n\n";
  o += "BU_:";
  for (std::string_view n : kNodeNames) o += " " + std::string(n);
  o += "\n\n";
  for (const MessageSpec& m : kMessages) {
    o += "\nBO_ " + std::to_string(m.id) + " " + std::string(m.name) + ": " + std::to_string(m.length) + " " +
         std::string(m.sender) + "\n";
    for (const SignalSpec& s : m.signals) {
      o += " SG_ " + std::string(s.name) + " : " + std::to_string(s.start_bit) + "|" + std::to_string(s.bit_length) +
           "@1" + (s.kind == SignalKind::kUnsigned ? "+" : "-") + " (" + number(s.factor) + "," + number(s.offset) +
           ") [" + number(s.min) + "|" + number(s.max) + "] " + quoted(s.unit) + " " + receivers(m) + "\n";
    }
  }
  o += "\n\n";
  o += "CM_ \"gyrostab CAN FD bus (hil/can/frame_map.hpp, docs/can.md): 1 Mbit/s arbitration, 5 Mbit/s data. "
       "Every frame: byte 0 CRC-8 SAE J1850 over the id and bytes 1..len-1, byte 1 alive counter, bytes 2-3 "
       "tick tag.\";\n";
  for (const MessageSpec& m : kMessages) {
    o += "CM_ BO_ " + std::to_string(m.id) + " " + quoted(m.comment) + ";\n";
    for (const SignalSpec& s : m.signals)
      o += "CM_ SG_ " + std::to_string(m.id) + " " + std::string(s.name) + " " + quoted(s.comment) + ";\n";
  }
  o += "BA_DEF_  \"BusType\" STRING ;\n";
  o += "BA_DEF_ BO_  \"VFrameFormat\" ENUM  \"StandardCAN\",\"ExtendedCAN\",\"reserved\",\"reserved\",\"reserved\","
       "\"reserved\",\"reserved\",\"reserved\",\"reserved\",\"reserved\",\"reserved\",\"reserved\",\"reserved\","
       "\"reserved\",\"StandardCAN_FD\",\"ExtendedCAN_FD\";\n";
  o += "BA_DEF_ BO_  \"CANFD_BRS\" ENUM  \"0\",\"1\";\n";
  o += "BA_DEF_DEF_  \"BusType\" \"CAN FD\";\n";
  o += "BA_DEF_DEF_  \"VFrameFormat\" \"StandardCAN\";\n";
  o += "BA_DEF_DEF_  \"CANFD_BRS\" \"1\";\n";
  o += "BA_ \"BusType\" \"CAN FD\";\n";
  for (const MessageSpec& m : kMessages) o += "BA_ \"VFrameFormat\" BO_ " + std::to_string(m.id) + " 14;\n";
  for (const MessageSpec& m : kMessages)
    for (const SignalSpec& s : m.signals)
      if (s.kind == SignalKind::kDouble)
        o += "SIG_VALTYPE_ " + std::to_string(m.id) + " " + std::string(s.name) + " : 2;\n";
  return o;
}

}  // namespace gyrostab::can
