#include "hil/can/dbc_writer.hpp"

#include <cstdio>
#include <string_view>
#include <vector>

#include "hil/can/bus_nodes.hpp"

namespace gyrostab::can {
namespace {

// Shortest text that reads back as the same double (%.17g round-trips every finite double).
std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// DBC's placeholder for a message no node of the file receives.
constexpr std::string_view kNoReceiver = "Vector__XXX";

std::string receivers(const DeviceBus& bus, const MessageSpec& m) {
  if (m.direction == Direction::kSensor) return "controller";
  if (m.node != "controller") return std::string(m.node);
  std::string r;
  for (std::string_view n : command_receivers(bus)) r += (r.empty() ? "" : ",") + std::string(n);
  return r.empty() ? std::string(kNoReceiver) : r;
}

// DBC comments are double-quoted strings: no quotes inside.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"') ? '\'' : c;
  return out + "\"";
}

}  // namespace

std::string dbc_text(const DeviceBus& bus) {
  const std::span<const MessageSpec> messages = bus.messages();
  std::vector<const MessageSpec*> on_bus;
  for (const MessageSpec& m : messages) on_bus.push_back(&m);
  std::string o;
  o += "VERSION \"gyrostab-can-2\"\n\n\n";
  o += "NS_ :\n\tCM_\n\tBA_DEF_\n\tBA_\n\tBA_DEF_DEF_\n\tSIG_VALTYPE_\n\n";
  o += "BS_:\n\n";
  o += "BU_:";
  for (std::string_view n : bus_nodes(bus)) o += " " + std::string(n);
  o += "\n\n";
  for (const MessageSpec* mp : on_bus) {
    const MessageSpec& m = *mp;
    o += "\nBO_ " + std::to_string(m.id) + " " + std::string(m.name) + ": " + std::to_string(m.length) + " " +
         std::string(m.sender) + "\n";
    for (const SignalSpec& s : m.signals) {
      o += " SG_ " + std::string(s.name) + " : " + std::to_string(s.start_bit) + "|" + std::to_string(s.bit_length) +
           "@1" + (s.kind == SignalKind::kUnsigned ? "+" : "-") + " (" + number(s.factor) + "," + number(s.offset) +
           ") [" + number(s.min) + "|" + number(s.max) + "] " + quoted(s.unit) + " " + receivers(bus, m) + "\n";
    }
  }
  o += "\n\n";
  char fp[24];
  std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(bus.map->fingerprint));
  o += "CM_ \"gyrostab CAN FD bus of device " + std::string(bus.map->device) + " (map generated from its signal "
       "table, fingerprint " + fp + "; docs/can.md): 1 Mbit/s arbitration, 5 Mbit/s data. Every frame: byte 0 "
       "CRC-8 SAE J1850 over the id and bytes 1..len-1, byte 1 alive counter, bytes 2-3 tick tag.\";\n";
  for (const MessageSpec* mp : on_bus) {
    const MessageSpec& m = *mp;
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
  for (const MessageSpec* m : on_bus) o += "BA_ \"VFrameFormat\" BO_ " + std::to_string(m->id) + " 14;\n";
  for (const MessageSpec* m : on_bus)
    for (const SignalSpec& s : m->signals)
      if (s.kind == SignalKind::kDouble)
        o += "SIG_VALTYPE_ " + std::to_string(m->id) + " " + std::string(s.name) + " : 2;\n";
  return o;
}

}  // namespace gyrostab::can
