// candump's log format (can-utils `candump -l` / `-L`, replayable with `canplayer -I FILE`), one frame a line:
//   (1735270496.916858) vcan0 1A0##5<96 hex digits>      CAN FD: ID##<flags nibble><data>
//   (1735270496.916858) vcan0 123#DEADBEEF               classic: ID#<data, 0..8 bytes>
//   (1735270496.916858) vcan0 123#R                      remote frame
// ID: 3 hex digits for 11-bit, 8 for 29-bit identifiers (an error frame is a 29-bit-style id with bit 29,
// CAN_ERR_FLAG, set). The FD flags nibble is the kernel's canfd_frame.flags: 1 BRS, 2 ESI, 4 FDF — candump on
// a recent kernel writes "5" for a frame sent with bit-rate switch, and so does this writer, so a log
// recorded by gyrostab and one recorded by candump from the same traffic are identical line for line. Lines
// that do not start with '(' are comments (canplayer skips them): gyrostab writes its header there.
// Timestamps: seconds and microseconds; gyrostab's lockstep logs use the simulated time of the frame's tick
// (deterministic logs that canplayer replays at the scene's real rate), real-time runs the kernel's receive
// time.
//
// format_candump_line and parse_candump_line work on caller buffers (no heap: the writer runs in the loop;
// the parser is a fuzz target). CandumpWriter buffers through stdio; CandumpReader loads a whole file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "hil/can/can_frame.hpp"

namespace gyrostab::can {

// Longest line: "(" 20 "." 6 ") " ifname(15) " " 8 "##" 1 128 "\n".
inline constexpr std::size_t kMaxCandumpLine = 200;

// Writes one log line (with '\n') into buf; returns its length, 0 if cap is too small or ifname too long.
std::size_t format_candump_line(const CanFrame& f, std::string_view ifname, std::int64_t time_ns, char* buf,
                                std::size_t cap);

enum class CandumpParse { kFrame, kSkip, kError };

// One line (without or with its '\n'): kFrame fills `out` (time in out.time_ns) and `ifname` (a view into
// `line`); kSkip for comment and empty lines; kError for a line that starts with '(' but is not a frame.
CandumpParse parse_candump_line(std::string_view line, CanFrame& out, std::string_view& ifname);

class CandumpWriter {
 public:
  CandumpWriter() = default;
  ~CandumpWriter();
  CandumpWriter(const CandumpWriter&) = delete;
  CandumpWriter& operator=(const CandumpWriter&) = delete;

  // Creates `path` and writes the comment header lines (each prefixed with "# "). Start-up only (allocates).
  bool open(const std::string& path, const std::string& ifname, const std::vector<std::string>& header,
            std::string& error);
  // One frame; false once a write failed (then failed() stays true).
  bool write(const CanFrame& f, std::int64_t time_ns);
  bool close(std::string& error);
  bool failed() const { return failed_; }
  std::uint64_t frames_written() const { return frames_; }

 private:
  std::FILE* file_{nullptr};
  char ifname_[16]{};
  std::size_t ifname_len_{0};
  bool failed_{false};
  std::uint64_t frames_{0};
  std::string path_;
};

struct CandumpRecord {
  CanFrame frame;
  std::string ifname;
  int line{0};
};

struct CandumpFile {
  std::vector<std::string> comments;  // the text of the comment lines ("# " stripped)
  std::vector<CandumpRecord> frames;
};

// Reads a whole candump log. false with `error` ("FILE:LINE: ...") on an unreadable file or a bad frame line.
bool read_candump_file(const std::string& path, CandumpFile& out, std::string& error);

// True if the file's first line that is not empty or a comment starts like a candump frame line ("(" digits
// "." digits ")"): how `gyrostab replay` tells a candump log from an LCM log.
bool looks_like_candump_log(const std::string& path);

}  // namespace gyrostab::can
