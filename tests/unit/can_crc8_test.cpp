// CRC-8 SAE J1850 of the CAN envelope (hil/can/crc8.hpp) against published vectors: the catalogue check value
// (CRC-8/SAE-J1850, "123456789" → 0x4B) and the seven test vectors of the AUTOSAR Classic "Specification of
// CRC Routines" (8-bit SAE J1850 table). Exact integer results: any difference is a wrong parameter.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hil/can/crc8.hpp"
#include "hil/can/frame_codec.hpp"

namespace gyrostab::can {
namespace can_crc8_test {

std::uint8_t crc(const std::vector<std::uint8_t>& v) {
  return crc8_sae_j1850(v.data(), v.size());
}

TEST(CanCrc8, CatalogueCheckValue) {
  const std::vector<std::uint8_t> digits = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc(digits), 0x4B);
}

TEST(CanCrc8, AutosarSaeJ1850Vectors) {
  EXPECT_EQ(crc({0x00, 0x00, 0x00, 0x00}), 0x59);
  EXPECT_EQ(crc({0xF2, 0x01, 0x83}), 0x37);
  EXPECT_EQ(crc({0x0F, 0xAA, 0x00, 0x55}), 0x79);
  EXPECT_EQ(crc({0x00, 0xFF, 0x55, 0x11}), 0xB8);
  EXPECT_EQ(crc({0x33, 0x22, 0x55, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF}), 0xCB);
  EXPECT_EQ(crc({0x92, 0x6B, 0x55}), 0x8C);
  EXPECT_EQ(crc({0xFF, 0xFF, 0xFF, 0xFF}), 0x74);
}

TEST(CanCrc8, IncrementalEqualsOneShot) {
  const std::uint8_t data[] = {0x33, 0x22, 0x55, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF};
  const std::uint8_t reg = crc8_update(crc8_update(kCrc8Init, data, 4), data + 4, 5);
  EXPECT_EQ(crc8_finish(reg), 0xCB);
}

// The envelope CRC covers the identifier: the same payload on another id has another CRC (for this payload;
// a CRC-8 cannot make that true of every payload, only 255 in 256).
TEST(CanCrc8, FrameCrcCoversTheIdentifier) {
  std::uint8_t data[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::uint8_t id_bytes_a[] = {0xA0, 0x01, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(frame_crc(0x1A0, data, 8), crc8_sae_j1850(id_bytes_a, sizeof id_bytes_a));
  EXPECT_NE(frame_crc(0x1A0, data, 8), frame_crc(0x190, data, 8));
}

}  // namespace can_crc8_test
}  // namespace gyrostab::can
