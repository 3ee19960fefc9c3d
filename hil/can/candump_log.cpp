#include "hil/can/candump_log.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace gyrostab::can {
namespace {

// CAN_ERR_FLAG of <linux/can.h>: marks an error frame's identifier in candump's text.
constexpr std::uint32_t kCanErrFlag = 0x20000000u;
constexpr char kHex[] = "0123456789ABCDEF";

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// Writes the decimal digits of v, zero-padded to `width`, at p; returns the number written.
std::size_t put_decimal(char* p, std::uint64_t v, int width) {
  char tmp[24];
  int n = 0;
  do {
    tmp[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0 && n < 24);
  while (n < width && n < 24) tmp[n++] = '0';
  for (int i = 0; i < n; ++i) p[i] = tmp[n - 1 - i];
  return static_cast<std::size_t>(n);
}

}  // namespace

std::size_t format_candump_line(const CanFrame& f, std::string_view ifname, std::int64_t time_ns, char* buf,
                                std::size_t cap) {
  if (cap < kMaxCandumpLine || ifname.empty() || ifname.size() > 15) return 0;
  const std::size_t len = f.len > (f.fd() ? kFdMaxData : kClassicMaxData) ? (f.fd() ? kFdMaxData : kClassicMaxData)
                                                                            : f.len;
  // Negative times (never written by gyrostab) clamp to 0: candump's fields are unsigned.
  const std::uint64_t t = time_ns < 0 ? 0 : static_cast<std::uint64_t>(time_ns);
  std::size_t n = 0;
  buf[n++] = '(';
  n += put_decimal(buf + n, t / 1'000'000'000u, 10);
  buf[n++] = '.';
  n += put_decimal(buf + n, (t % 1'000'000'000u) / 1000u, 6);
  buf[n++] = ')';
  buf[n++] = ' ';
  std::memcpy(buf + n, ifname.data(), ifname.size());
  n += ifname.size();
  buf[n++] = ' ';
  const bool error = (f.flags & kFlagError) != 0;
  const bool extended = (f.flags & kFlagExtended) != 0 || error;
  std::uint32_t id = f.id;
  if (error) id = (id & 0x1FFFFFFFu) | kCanErrFlag;
  const int digits = extended ? 8 : 3;
  for (int i = digits - 1; i >= 0; --i) buf[n++] = kHex[(id >> (4 * i)) & 0xFu];
  buf[n++] = '#';
  if (f.fd()) {
    buf[n++] = '#';
    // Kernel canfd_frame.flags: CANFD_BRS 1, CANFD_ESI 2, CANFD_FDF 4 (set on every FD frame received).
    unsigned flags = 4u;
    if ((f.flags & kFlagBrs) != 0) flags |= 1u;
    if ((f.flags & kFlagEsi) != 0) flags |= 2u;
    buf[n++] = kHex[flags];
  } else if ((f.flags & kFlagRemote) != 0) {
    buf[n++] = 'R';
    if (len > 0) buf[n++] = static_cast<char>('0' + len);  // the requested length, as newer candump writes it
    buf[n++] = '\n';
    return n;
  }
  for (std::size_t i = 0; i < len; ++i) {
    buf[n++] = kHex[f.data[i] >> 4];
    buf[n++] = kHex[f.data[i] & 0xFu];
  }
  buf[n++] = '\n';
  return n;
}

CandumpParse parse_candump_line(std::string_view line, CanFrame& out, std::string_view& ifname) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
  if (line.empty() || line.front() != '(') return CandumpParse::kSkip;
  out = CanFrame{};
  std::size_t i = 1;
  std::uint64_t sec = 0;
  std::size_t start = i;
  while (i < line.size() && is_digit(line[i])) {
    if (i - start >= 11) return CandumpParse::kError;
    sec = sec * 10 + static_cast<std::uint64_t>(line[i] - '0');
    ++i;
  }
  // Times are kept as int64 nanoseconds: up to the year 2262.
  if (i == start || i >= line.size() || line[i] != '.' || sec > 9'223'372'035u) return CandumpParse::kError;
  ++i;
  start = i;
  std::uint64_t usec = 0;
  while (i < line.size() && is_digit(line[i])) {
    if (i - start >= 6) return CandumpParse::kError;
    usec = usec * 10 + static_cast<std::uint64_t>(line[i] - '0');
    ++i;
  }
  if (i - start != 6 || i >= line.size() || line[i] != ')') return CandumpParse::kError;
  ++i;
  out.time_ns = static_cast<std::int64_t>(sec * 1'000'000'000u + usec * 1000u);
  if (i >= line.size() || line[i] != ' ') return CandumpParse::kError;
  ++i;
  start = i;
  while (i < line.size() && line[i] != ' ') ++i;
  if (i == start || i - start > 15 || i >= line.size()) return CandumpParse::kError;
  ifname = line.substr(start, i - start);
  ++i;
  // Identifier.
  start = i;
  std::uint32_t id = 0;
  while (i < line.size() && line[i] != '#') {
    const int h = hex_value(line[i]);
    if (h < 0 || i - start >= 8) return CandumpParse::kError;
    id = (id << 4) | static_cast<std::uint32_t>(h);
    ++i;
  }
  const std::size_t id_digits = i - start;
  if (i >= line.size() || (id_digits != 3 && id_digits != 8)) return CandumpParse::kError;
  ++i;  // '#'
  if (id_digits == 3) {
    if (id > 0x7FFu) return CandumpParse::kError;
  } else if ((id & kCanErrFlag) != 0) {
    out.flags |= kFlagError;
    id &= 0x1FFFFFFFu;
  } else {
    if (id > 0x1FFFFFFFu) return CandumpParse::kError;
    out.flags |= kFlagExtended;
  }
  out.id = id;
  std::size_t max_len = kClassicMaxData;
  if (i < line.size() && line[i] == '#') {
    ++i;
    if (i >= line.size()) return CandumpParse::kError;
    const int flags = hex_value(line[i]);
    if (flags < 0 || (out.flags & kFlagError) != 0) return CandumpParse::kError;
    out.flags |= kFlagFd;
    if ((flags & 1) != 0) out.flags |= kFlagBrs;
    if ((flags & 2) != 0) out.flags |= kFlagEsi;
    ++i;
    max_len = kFdMaxData;
  } else if (i < line.size() && (line[i] == 'R' || line[i] == 'r')) {
    out.flags |= kFlagRemote;
    ++i;
    if (i < line.size() && is_digit(line[i])) {  // newer can-utils: the requested length
      out.len = static_cast<std::uint8_t>(line[i] - '0');
      if (out.len > 8) return CandumpParse::kError;
      ++i;
    }
  }
  if ((out.flags & kFlagRemote) == 0) {
    std::size_t n = 0;
    while (i < line.size() && line[i] != ' ') {
      if (line[i] == '.') {  // cansend's optional byte separator
        ++i;
        continue;
      }
      if (i + 1 >= line.size()) return CandumpParse::kError;
      const int hi = hex_value(line[i]);
      const int lo = hex_value(line[i + 1]);
      if (hi < 0 || lo < 0 || n >= max_len) return CandumpParse::kError;
      out.data[n++] = static_cast<std::uint8_t>((hi << 4) | lo);
      i += 2;
    }
    if (out.fd() && !fd_length_valid(n)) return CandumpParse::kError;
    out.len = static_cast<std::uint8_t>(n);
  }
  // candump -x appends a direction field (" T" / " R"): accepted and ignored; nothing else may follow.
  if (i < line.size()) {
    const std::string_view rest = line.substr(i);
    if (rest != " T" && rest != " R") return CandumpParse::kError;
  }
  return CandumpParse::kFrame;
}

// --- CandumpWriter -----------------------------------------------------------------------------------------

CandumpWriter::~CandumpWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

bool CandumpWriter::open(const std::string& path, const std::string& ifname, const std::vector<std::string>& header,
                         std::string& error) {
  if (ifname.empty() || ifname.size() > 15) {
    error = "candump log: interface name '" + ifname + "' must have 1 to 15 characters";
    return false;
  }
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error = "cannot create " + path + ": " + std::strerror(errno);
    return false;
  }
  path_ = path;
  std::memcpy(ifname_, ifname.data(), ifname.size());
  ifname_len_ = ifname.size();
  for (const std::string& h : header) {
    if (std::fprintf(file_, "# %s\n", h.c_str()) < 0) failed_ = true;
  }
  if (failed_) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

bool CandumpWriter::write(const CanFrame& f, std::int64_t time_ns) {
  if (file_ == nullptr || failed_) return false;
  char line[kMaxCandumpLine];
  const std::size_t n = format_candump_line(f, std::string_view(ifname_, ifname_len_), time_ns, line, sizeof line);
  if (n == 0 || std::fwrite(line, 1, n, file_) != n) {
    failed_ = true;
    return false;
  }
  ++frames_;
  return true;
}

bool CandumpWriter::close(std::string& error) {
  if (file_ == nullptr) return !failed_;
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed_ || !flushed || !closed) {
    error = "candump log " + path_ + ": a write failed";
    return false;
  }
  return true;
}

// --- reading -----------------------------------------------------------------------------------------------

bool read_candump_file(const std::string& path, CandumpFile& out, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open " + path;
    return false;
  }
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    CandumpRecord r;
    std::string_view ifname;
    switch (parse_candump_line(line, r.frame, ifname)) {
      case CandumpParse::kFrame:
        r.ifname = std::string(ifname);
        r.line = number;
        out.frames.push_back(r);
        break;
      case CandumpParse::kSkip:
        if (!line.empty() && line[0] == '#') out.comments.push_back(line.size() > 2 ? line.substr(2) : "");
        break;
      case CandumpParse::kError: {
        std::ostringstream m;
        m << path << ":" << number << ": not a candump frame line: " << line.substr(0, 120);
        error = m.str();
        return false;
      }
    }
  }
  return true;
}

bool looks_like_candump_log(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string line;
  int lines = 0;
  while (lines < 64 && std::getline(in, line)) {
    ++lines;
    if (line.empty() || line[0] == '#') continue;
    CanFrame f;
    std::string_view ifname;
    return parse_candump_line(line, f, ifname) == CandumpParse::kFrame;
  }
  return lines > 0 && in.eof();  // comments only: an empty candump log
}

}  // namespace gyrostab::can
