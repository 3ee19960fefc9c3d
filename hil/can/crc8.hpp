// CRC-8 SAE J1850 protecting every cyclic frame of the CAN bus (hil/can/frame_map.hpp, docs/can.md).
//
// Parameters (Rocksoft model, as in the AUTOSAR Classic "Specification of CRC Routines", Crc_CalculateCRC8,
// and the CRC catalogue entry CRC-8/SAE-J1850): width 8, polynomial 0x1D (x^8 + x^4 + x^3 + x^2 + 1),
// init 0xFF, no reflection in or out, final XOR 0xFF; check value CRC("123456789") = 0x4B.
// Why this polynomial: it is the one of AUTOSAR E2E profiles 1 and 2 on CAN, which drive and sensor vendors
// already implement. Any CRC-8 with a non-zero x^0 term detects every error burst up to 8 bits; a random
// corruption passes with probability 2^-8. The bus's own frame CRC (15/17/21 bits) stays the first line of
// defence; this one catches what happens above the bus (a stale buffer, a gateway, a frame on the wrong id:
// the identifier is part of what it covers, see frame_map.hpp).
//
// Table-driven, constexpr, no heap: usable in firmware and in a libFuzzer target. O(n) for n bytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace gyrostab::can {

inline constexpr std::uint8_t kCrc8Polynomial = 0x1D;
inline constexpr std::uint8_t kCrc8Init = 0xFF;
inline constexpr std::uint8_t kCrc8XorOut = 0xFF;

namespace detail {
constexpr std::array<std::uint8_t, 256> make_crc8_table() {
  std::array<std::uint8_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 0x80u) ? ((crc << 1) ^ kCrc8Polynomial) : (crc << 1);
    t[i] = static_cast<std::uint8_t>(crc & 0xFFu);
  }
  return t;
}
inline constexpr std::array<std::uint8_t, 256> kCrc8Table = make_crc8_table();
}  // namespace detail

// Running register (before the final XOR): start with kCrc8Init, feed bytes, finish with crc8_finish.
constexpr std::uint8_t crc8_update(std::uint8_t reg, const std::uint8_t* data, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) reg = detail::kCrc8Table[static_cast<std::uint8_t>(reg ^ data[i])];
  return reg;
}
constexpr std::uint8_t crc8_finish(std::uint8_t reg) {
  return static_cast<std::uint8_t>(reg ^ kCrc8XorOut);
}

// CRC-8 SAE J1850 of n bytes.
constexpr std::uint8_t crc8_sae_j1850(const std::uint8_t* data, std::size_t n) {
  return crc8_finish(crc8_update(kCrc8Init, data, n));
}

}  // namespace gyrostab::can
