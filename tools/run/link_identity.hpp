// Who this process is on a plant ⇄ controller link (hil/link/link_guard.hpp, docs/transport.md): the plant
// draws the session id (or takes `--session`, as `gyrostab run --transport ...` gives the same one to both
// children), the controller draws its own id and takes `--session` if given (else it binds at the handshake),
// and both read the link key of `--key-file` if given.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "firmware/link/secoc.hpp"
#include "tools/run/run_role.hpp"

namespace gyrostab::tools {

struct LinkIdentity {
  std::uint64_t session{0};  // 0: the controller binds at the handshake
  std::uint64_t own_id{0};
  std::uint64_t peer{0};     // the plant: its controller's id when given (--controller-id); 0: the handshake's
  std::optional<firmware::link::Key128> key;
};

// "" or why the request's --key-file cannot be used (unreadable, too open, not a key): checked by the parent of
// a process pair before it touches the output directory or starts a child.
std::string key_file_problem(const TransportOptions& t);

// false with `error` set: the OS random source failed, or the key file is refused.
bool link_identity(const TransportOptions& t, bool plant_side, LinkIdentity& out, std::string& error);

// A key file: 32 hexadecimal digits (16 bytes), whitespace and `#` comments allowed, readable by its owner
// only (like ssh's keys). false with `error` set otherwise.
bool read_key_file(const std::string& path, firmware::link::Key128& key, std::string& error);

// A session id as the command line and report.json write it (0x and 8 hexadecimal digits).
std::string format_link_id(std::uint64_t id);
// Parses "0x1234abcd" or a decimal number in [1, 2^32); false otherwise.
bool parse_link_id(const std::string& text, std::uint64_t& id);

}  // namespace gyrostab::tools
