// Consistent Overhead Byte Stuffing (Cheshire & Baker, "Consistent Overhead Byte Stuffing", IEEE/ACM Trans.
// Networking 7(2), 1999): a frame of n bytes becomes at most n + ⌈n/254⌉ bytes with no zero byte, so a single
// 0x00 ends every frame on a byte stream (the target link's UART or FIFO: firmware/link/target_frame.hpp).
// A receiver that joins mid-stream, or loses bytes, resynchronises at the next zero; a corrupted length byte
// can only damage the frame it is in. Chosen over SLIP or HDLC byte stuffing for its bounded overhead
// (1 byte per frame here, frames < 254 bytes) rather than up to 2x.
// No heap; O(n). Tested by tests/unit/target_frame_test.cpp and the fuzz target tests/fuzz/target_frame_fuzz.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace gyrostab::firmware::link {

// Largest encoded size of an n-byte frame, without the closing zero.
constexpr std::size_t cobs_max_encoded(std::size_t n) { return n + n / 254 + 1; }

// Encodes `in` into `out` (no closing zero). Returns the encoded length, 0 when `out` is too small.
constexpr std::size_t cobs_encode(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  if (out.size() < cobs_max_encoded(in.size())) return 0;
  std::size_t code_at = 0;  // where the current block's length byte goes
  std::size_t w = 1;
  std::uint8_t code = 1;
  for (const std::uint8_t b : in) {
    if (b == 0) {
      out[code_at] = code;
      code_at = w++;
      code = 1;
      continue;
    }
    out[w++] = b;
    if (++code == 0xFF) {
      out[code_at] = code;
      code_at = w++;
      code = 1;
    }
  }
  out[code_at] = code;
  return w;
}

// Decodes one frame `in` (the bytes between two zeros, zeros excluded) into `out`. Returns the decoded
// length, or -1 when the input is not valid COBS (a zero inside, a block running past the end) or `out` is
// too small.
constexpr long cobs_decode(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  std::size_t r = 0;
  std::size_t w = 0;
  while (r < in.size()) {
    const std::uint8_t code = in[r++];
    if (code == 0) return -1;
    const std::size_t block = code - 1u;
    if (r + block > in.size()) return -1;
    for (std::size_t i = 0; i < block; ++i) {
      const std::uint8_t b = in[r++];
      if (b == 0 || w >= out.size()) return -1;
      out[w++] = b;
    }
    if (code != 0xFF && r < in.size()) {
      if (w >= out.size()) return -1;
      out[w++] = 0;
    }
  }
  return static_cast<long>(w);
}

}  // namespace gyrostab::firmware::link
