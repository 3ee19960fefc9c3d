// CRC-32 as Ethernet, zlib and PNG compute it (polynomial 0x04C11DB7, reflected: 0xEDB88320; initial value and
// final xor 0xFFFFFFFF; check value of "123456789" = 0xCBF43926). The target link's frames carry it
// (firmware/link/target_frame.hpp): 32 bits detect every burst of up to 32 bit errors and every odd number of
// errors in the frame lengths used here, which an 8-bit CRC (CAN's per-frame check) does not for 150 bytes.
// A 256-entry table (1 KB of flash, built at compile time) keeps it at about 6 instructions per byte.
// Constant-time in the data, no heap. Tested by tests/unit/target_frame_test.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace gyrostab::firmware::link {

namespace detail {
constexpr std::array<std::uint32_t, 256> make_crc32_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}
inline constexpr std::array<std::uint32_t, 256> kCrc32Table = make_crc32_table();
}  // namespace detail

constexpr std::uint32_t crc32(std::span<const std::uint8_t> data) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const std::uint8_t b : data) c = detail::kCrc32Table[(c ^ b) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

}  // namespace gyrostab::firmware::link
