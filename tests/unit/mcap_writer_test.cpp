// The MCAP writer's framing against the specification, on a small file: the CRC-32 check value, the magic at
// both ends, the footer's offsets pointing at the summary and its offsets, the summary CRC, and a message
// record where the chunk's message index says it is. (Every shipped scene's file is also read back by an
// independent reader, @mcap/core: label mcap.)
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "tools/log/mcap_writer.hpp"

namespace gyrostab {
namespace mcap_writer_test {

std::uint64_t u64_at(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}
std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

TEST(McapWriter, Crc32CheckValue) {
  EXPECT_EQ(mcap::crc32(0, "123456789", 9), 0xCBF43926u);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(mcap::crc32(mcap::crc32(0, "1234", 4), "56789", 5), 0xCBF43926u);  // continued
}

TEST(McapWriter, FramingOfASmallFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "gyrostab_mcap_writer_test.mcap").string();
  mcap::Writer w;
  std::string error;
  mcap::WriterOptions o;
  o.chunk_size = 200;  // several chunks
  ASSERT_TRUE(w.open(path, o, error)) << error;
  const auto schema = w.add_schema("s", "jsonschema", R"({"type":"object"})");
  const auto ch = w.add_channel(schema, "/t", "json");
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(w.write(ch, 1000u * i, 1000u * i, "{\"x\":" + std::to_string(i) + "}"));
  ASSERT_TRUE(w.close(error)) << error;
  std::ifstream f(path, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  const std::string magic("\x89MCAP0\r\n", 8);
  ASSERT_GT(b.size(), 100u);
  EXPECT_EQ(b.substr(0, 8), magic);
  EXPECT_EQ(b.substr(b.size() - 8), magic);
  EXPECT_EQ(b[8], '\x01');  // the header record first
  // Footer: opcode, length 20, summary start, summary offset start, CRC; then the magic.
  const std::size_t footer = b.size() - 8 - 1 - 8 - 20;
  ASSERT_EQ(b[footer], '\x02');
  EXPECT_EQ(u64_at(b, footer + 1), 20u);
  const std::uint64_t summary = u64_at(b, footer + 9), offsets = u64_at(b, footer + 17);
  ASSERT_LT(summary, offsets);
  ASSERT_LT(offsets, footer);
  EXPECT_EQ(b[summary], '\x03');  // the schema group first
  EXPECT_EQ(b[offsets], '\x0E');  // a summary-offset record
  EXPECT_EQ(b[summary - 13], '\x0F');  // data end just before the summary
  EXPECT_EQ(u32_at(b, summary - 4), mcap::crc32(0, b.data(), summary - 13));
  EXPECT_EQ(u32_at(b, footer + 25), mcap::crc32(0, b.data() + summary, footer + 25 - summary));
  // The first chunk after the header: its message index follows it and points at a message record.
  const std::size_t chunk = 8 + 1 + 8 + u64_at(b, 9);
  ASSERT_EQ(b[chunk], '\x06');
  const std::size_t chunk_len = 1 + 8 + u64_at(b, chunk + 1);
  const std::size_t body = chunk + 9;
  const std::uint32_t compression_len = u32_at(b, body + 28);
  EXPECT_EQ(compression_len, 0u);
  const std::size_t records = body + 32 + 8;
  EXPECT_EQ(u32_at(b, body + 24), mcap::crc32(0, b.data() + records, u64_at(b, body + 32)));
  const std::size_t index = chunk + chunk_len;
  ASSERT_EQ(b[index], '\x07');
  const std::uint64_t first_offset = u64_at(b, index + 9 + 2 + 4 + 8);
  EXPECT_EQ(b[records + first_offset], '\x05');
}

}  // namespace mcap_writer_test
}  // namespace gyrostab
