// libFuzzer target for the target link's decoder (firmware/link/target_frame.hpp, cobs.hpp, crc32.hpp): the
// arbitrary bytes are a stream from the other end, fed byte by byte through collect() and judge() in both
// directions, bound to a session after the first byte (its value picks whether and to what).
// Invariants beyond "no crash, no sanitizer report": every complete frame is accepted or refused with exactly
// one cause (accepted + refused = frames judged); an accepted frame's payload has its kind's length (a
// configuration at most kMaxConfigBytes) and, once bound, the bound session and sender; an accepted frame
// re-encoded by the encoder decodes to the same payload. Built with -DGYROSTAB_FUZZ=ON (clang); run with
// tools/fuzz/run-all target_frame_fuzz.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "firmware/link/target_frame.hpp"

namespace {

using gyrostab::firmware::link::TargetFrameDecoder;
using gyrostab::firmware::link::TargetFrameEncoder;
using gyrostab::firmware::link::TargetFrameKind;
using gyrostab::firmware::link::TargetFrameView;
using gyrostab::firmware::link::TargetRxVerdict;

// The frames of a device with 5 sensor values and 2 commands (the monorail's table).
constexpr gyrostab::firmware::link::TargetFrameSizes kFrames = gyrostab::firmware::link::target_frame_sizes(5, 2);

void run(const std::uint8_t* data, std::size_t size, bool from_host) {
  TargetFrameDecoder dec(from_host, kFrames);
  std::uint32_t session = 0, sender = 0;
  if (size > 0 && (data[0] & 1u) != 0) {
    session = 9;
    sender = (data[0] & 2u) != 0 ? 7 : 0;
    dec.bind(session, sender);
  }
  for (std::size_t i = 0; i < size; ++i) {
    std::span<const std::uint8_t> wire;
    if (!dec.collect(data[i], wire)) continue;
    TargetFrameView v;
    const std::uint64_t before = dec.counters().accepted + dec.counters().refused();
    const TargetRxVerdict r = dec.judge(wire, v);
    if (dec.counters().accepted + dec.counters().refused() != before + 1) __builtin_trap();  // one cause each
    if (r != TargetRxVerdict::kOk) continue;
    const long want = gyrostab::firmware::link::target_payload_bytes(v.kind, kFrames);
    if (want >= 0 ? v.payload.size() != static_cast<std::size_t>(want)
                  : v.payload.size() > gyrostab::firmware::link::kMaxConfigBytes) {
      __builtin_trap();
    }
    if (session != 0 && (v.session != session || (sender != 0 && v.sender != sender))) __builtin_trap();
    if (gyrostab::firmware::link::sent_by_host(v.kind) != from_host) __builtin_trap();
    // Re-encoded by the other end's encoder and judged by a fresh decoder: the same payload.
    static std::uint8_t copy[gyrostab::firmware::link::kMaxTargetPayload];
    const std::size_t n = v.payload.size();
    std::memcpy(copy, v.payload.data(), n);
    TargetFrameEncoder enc(v.sender, v.session);
    const std::span<const std::uint8_t> again = enc.encode(v.kind, copy, n);
    TargetFrameDecoder fresh(from_host, kFrames);
    TargetFrameView w;
    if (again.empty() || fresh.judge(again.first(again.size() - 1), w) != TargetRxVerdict::kOk ||
        w.payload.size() != n || std::memcmp(w.payload.data(), copy, n) != 0) {
      __builtin_trap();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  run(data, size, true);
  run(data, size, false);
  return 0;
}
