// candump log lines (hil/can/candump_log.hpp): the writer produces what can-utils' candump writes for the same
// frames (lines captured from candump 2020.11 on kernel 6.1 in the test VM), and the reader reads candump's
// lines back to the same frames; malformed lines are errors, comments are skipped.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "hil/can/candump_log.hpp"

namespace gyrostab::can {
namespace can_candump_test {

std::string format(const CanFrame& f, std::int64_t t_ns, std::string_view ifname = "vcan0") {
  char buf[kMaxCandumpLine];
  const std::size_t n = format_candump_line(f, ifname, t_ns, buf, sizeof buf);
  return std::string(buf, n);
}

CanFrame parse(const std::string& line, CandumpParse want = CandumpParse::kFrame) {
  CanFrame f;
  std::string_view ifname;
  EXPECT_EQ(parse_candump_line(line, f, ifname), want) << line;
  return f;
}

// Recorded with `candump -L vcan0` after `cansend vcan0 123#DEADBEEF` and
// `cansend vcan0 123##1.00112233445566778899AABBCCDDEEFF` (hil/vm/run-in-vm).
constexpr const char* kCandumpClassic = "(1795401624.807660) vcan0 123#DEADBEEF";
constexpr const char* kCandumpFd = "(1795401624.905444) vcan0 123##500112233445566778899AABBCCDDEEFF";

TEST(CanCandump, ReadsCandumpLines) {
  CanFrame c = parse(kCandumpClassic);
  EXPECT_EQ(c.id, 0x123u);
  EXPECT_FALSE(c.fd());
  EXPECT_EQ(c.len, 4);
  EXPECT_EQ(c.data[0], 0xDE);
  EXPECT_EQ(c.data[3], 0xEF);
  EXPECT_EQ(c.time_ns, 1795401624'807660'000);
  CanFrame d = parse(kCandumpFd);
  EXPECT_TRUE(d.fd());
  EXPECT_TRUE(d.flags & kFlagBrs);
  EXPECT_FALSE(d.flags & kFlagEsi);
  EXPECT_EQ(d.len, 16);
  EXPECT_EQ(d.data[15], 0xFF);
}

TEST(CanCandump, WritesWhatCandumpWrites) {
  EXPECT_EQ(format(parse(kCandumpClassic), 1795401624'807660'000), std::string(kCandumpClassic) + "\n");
  EXPECT_EQ(format(parse(kCandumpFd), 1795401624'905444'999), std::string(kCandumpFd) + "\n")
      << "microseconds truncate, as the kernel's timeval does";
}

TEST(CanCandump, RoundTripsEveryFrameKind) {
  CanFrame fd{};
  fd.id = 0x1A0;
  fd.len = 48;
  fd.flags = kFlagFd | kFlagBrs | kFlagEsi;
  for (int i = 0; i < 48; ++i) fd.data[i] = static_cast<std::uint8_t>(i * 5);
  CanFrame ext{};
  ext.id = 0x1ABCDEF0;
  ext.flags = kFlagExtended;
  ext.len = 8;
  CanFrame rtr{};
  rtr.id = 0x7FF;
  rtr.flags = kFlagRemote;
  CanFrame err{};
  err.id = 0x4;  // CAN_ERR_CRTL
  err.flags = kFlagError;
  err.len = 8;
  err.data[1] = 0x04;
  CanFrame empty{};
  empty.id = 0x000;
  for (const CanFrame& f : {fd, ext, rtr, err, empty}) {
    const std::string line = format(f, 12'000'001'000);
    const CanFrame back = parse(line);
    EXPECT_EQ(back.id, f.id) << line;
    EXPECT_EQ(back.flags, f.flags) << line;
    EXPECT_EQ(back.len, f.len) << line;
    EXPECT_EQ(std::memcmp(back.data, f.data, f.len), 0) << line;
    EXPECT_EQ(back.time_ns, 12'000'001'000) << line;
  }
  EXPECT_EQ(format(ext, 0), "(0000000000.000000) vcan0 1ABCDEF0#0000000000000000\n");
  EXPECT_EQ(format(err, 0), "(0000000000.000000) vcan0 20000004#0004000000000000\n");
  EXPECT_EQ(format(rtr, 0), "(0000000000.000000) vcan0 7FF#R\n");
}

TEST(CanCandump, CommentsAndBlankLinesAreSkipped) {
  parse("# gyrostab-can-log 1", CandumpParse::kSkip);
  parse("", CandumpParse::kSkip);
  parse("\n", CandumpParse::kSkip);
}

TEST(CanCandump, MalformedLinesAreErrors) {
  for (const char* bad : {
           "(",
           "(1.5) vcan0 123#00",                      // microseconds need 6 digits
           "(1.000000)vcan0 123#00",                  // missing space
           "(1.000000) vcan0 12#00",                  // 2-digit id
           "(1.000000) vcan0 800#00",                 // 11-bit id out of range
           "(1.000000) vcan0 123#001122334455667788", // 9 bytes classic
           "(1.000000) vcan0 123##5001122334455667788", // 9 bytes: not an FD length
           "(1.000000) vcan0 123#0",                  // half a byte
           "(1.000000) vcan0 123#GG",                 // not hex
           "(1.000000) vcan0 123#00 trailing",        // junk after the frame
           "(1.000000) averyveryverylongifname 123#00",
       }) {
    parse(bad, CandumpParse::kError);
  }
  parse("(1.000000) vcan0 123#0011 T");  // candump -x direction field
}

TEST(CanCandump, WriterAndReaderRoundTripAFile) {
  namespace fs = std::filesystem;
  const fs::path path = fs::temp_directory_path() / ("gyrostab_candump_" + std::to_string(::getpid()) + ".log");
  CanFrame f{};
  f.id = 0x181;
  f.len = 32;
  f.flags = kFlagFd | kFlagBrs;
  f.data[0] = 0x42;
  {
    CandumpWriter w;
    std::string error;
    ASSERT_TRUE(w.open(path.string(), "vcan0", {"gyrostab-candump 1", "scene test"}, error)) << error;
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(w.write(f, i * 1'000'000));
    ASSERT_TRUE(w.close(error)) << error;
    EXPECT_EQ(w.frames_written(), 3u);
  }
  EXPECT_TRUE(looks_like_candump_log(path.string()));
  CandumpFile file;
  std::string error;
  ASSERT_TRUE(read_candump_file(path.string(), file, error)) << error;
  ASSERT_EQ(file.comments.size(), 2u);
  EXPECT_EQ(file.comments[1], "scene test");
  ASSERT_EQ(file.frames.size(), 3u);
  EXPECT_EQ(file.frames[2].frame.time_ns, 2'000'000);
  EXPECT_EQ(file.frames[2].ifname, "vcan0");
  EXPECT_EQ(file.frames[2].line, 5);
  {
    std::ofstream(path, std::ios::app) << "(1.000000) vcan0 zz#00\n";
  }
  EXPECT_FALSE(read_candump_file(path.string(), file, error));
  EXPECT_NE(error.find(":6:"), std::string::npos) << error;
  fs::remove(path);
}

TEST(CanCandump, AnLcmLogIsNotACandumpLog) {
  namespace fs = std::filesystem;
  const fs::path path = fs::temp_directory_path() / ("gyrostab_notcandump_" + std::to_string(::getpid()));
  {
    std::ofstream out(path, std::ios::binary);
    const unsigned char lcm_magic[] = {0xED, 0xA1, 0xDA, 0x01, 0, 0, 0, 0, '\n', '(', '1'};
    out.write(reinterpret_cast<const char*>(lcm_magic), sizeof lcm_magic);
  }
  EXPECT_FALSE(looks_like_candump_log(path.string()));
  fs::remove(path);
}

}  // namespace can_candump_test
}  // namespace gyrostab::can
