#include "tools/run/link_identity.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "hil/link/link_guard.hpp"

namespace gyrostab::tools {

bool read_key_file(const std::string& path, firmware::link::Key128& key, std::string& error) {
  struct stat st{};
  if (stat(path.c_str(), &st) != 0) {
    error = "--key-file " + path + ": " + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "--key-file " + path + ": not a regular file";
    return false;
  }
  if ((st.st_mode & 077) != 0) {
    error = "--key-file " + path + ": readable or writable by others (chmod 600 " + path + ")";
    return false;
  }
  if (st.st_size > 4096) {
    error = "--key-file " + path + ": larger than 4 KiB (a key is 32 hexadecimal digits)";
    return false;
  }
  std::ifstream f(path);
  std::ostringstream text;
  text << f.rdbuf();
  std::string hex;
  std::istringstream lines(text.str());
  for (std::string line; std::getline(lines, line);) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    for (const char ch : line) {
      if (std::isspace(static_cast<unsigned char>(ch))) continue;
      if (!std::isxdigit(static_cast<unsigned char>(ch))) {
        error = "--key-file " + path + ": '" + std::string(1, ch) + "' is not a hexadecimal digit";
        return false;
      }
      hex += ch;
    }
  }
  if (hex.size() != 2 * key.bytes.size()) {
    error = "--key-file " + path + ": " + std::to_string(hex.size()) + " hexadecimal digits, a key has " +
            std::to_string(2 * key.bytes.size()) + " (128 bits)";
    return false;
  }
  for (std::size_t i = 0; i < key.bytes.size(); ++i) {
    key.bytes[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
  }
  return true;
}

std::string key_file_problem(const TransportOptions& t) {
  if (t.key_file.empty()) return "";
  firmware::link::Key128 key;
  std::string error;
  return read_key_file(t.key_file, key, error) ? "" : error;
}

bool link_identity(const TransportOptions& t, bool plant_side, LinkIdentity& out, std::string& error) {
  out = LinkIdentity{};
  if (!t.key_file.empty()) {
    firmware::link::Key128 key;
    if (!read_key_file(t.key_file, key, error)) return false;
    out.key = key;
  }
  const std::uint64_t drawn = hil::draw_link_id();
  if (drawn == 0) {
    error = "the OS's random source (getrandom) failed: cannot draw a link id";
    return false;
  }
  if (plant_side) {
    out.session = t.session != 0 ? t.session : drawn;
    out.own_id = out.session;
    out.peer = t.controller_id;
  } else {
    out.session = t.session;
    out.own_id = t.controller_id != 0 ? t.controller_id : drawn;
  }
  return true;
}

std::string format_link_id(std::uint64_t id) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%08llx", static_cast<unsigned long long>(id));
  return buf;
}

bool parse_link_id(const std::string& text, std::uint64_t& id) {
  if (text.empty() || text.size() > 20) return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
  if (errno != 0 || end == nullptr || *end != '\0' || v == 0 || v >= (1ull << 32)) return false;
  id = v;
  return true;
}

}  // namespace gyrostab::tools
