#include "hil/can/link_seal.hpp"

#include <array>

#include "firmware/link/siphash24.hpp"

namespace gyrostab::can {
namespace {

constexpr std::array<std::uint8_t, firmware::link::SipHash24::kKeyBytes> kNoKey{};

std::uint64_t load_le(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

void store_le(std::uint8_t* p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

std::uint64_t unkeyed_mac(std::span<const std::uint8_t> payload) {
  return firmware::link::siphash24(kNoKey, payload);
}

}  // namespace

hil::GuardConfig can_guard_config(hil::GuardConfig c) {
  c.profile.freshness_bytes = static_cast<std::uint8_t>(kLinkFreshnessBytes);
  return c;
}

std::size_t set_mac_payload(std::span<const CanFrame> set, std::uint64_t scene,
                            std::span<std::uint8_t, kMaxMacPayload> out) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const CanFrame& f = set[i];
    const bool header = i + 1 == set.size();
    const std::size_t end = header ? kLinkFreshnessByte : f.len;
    out[n++] = static_cast<std::uint8_t>(f.id & 0xFFu);
    out[n++] = static_cast<std::uint8_t>((f.id >> 8) & 0xFFu);
    for (std::size_t b = kTickTagByte; b < end && b < kFdMaxData; ++b) out[n++] = f.data[b];
  }
  store_le(out.data() + n, scene, 8);
  return n + 8;
}

hil::LinkEnvelope read_link_envelope(const CanFrame& h) {
  return hil::LinkEnvelope{load_le(h.data + kLinkSenderByte, 4), load_le(h.data + kLinkSessionByte, 4),
                           load_le(h.data + kLinkFreshnessByte, kLinkFreshnessBytes), load_le(h.data + kLinkMacByte, 8)};
}

void write_link_envelope(CanFrame& h, const hil::LinkEnvelope& e) {
  store_le(h.data + kLinkSenderByte, e.sender, 4);
  store_le(h.data + kLinkSessionByte, e.session, 4);
  store_le(h.data + kLinkFreshnessByte, e.freshness, kLinkFreshnessBytes);
  store_le(h.data + kLinkMacByte, e.mac, 8);
  h.data[kCrcByte] = frame_crc(h.id, h.data, h.len);
}

void seal(std::span<CanFrame> set, hil::LinkGuard& guard) {
  if (set.empty()) return;
  CanFrame& header = set.back();
  write_link_envelope(header, guard.header());  // the MAC covers sender and session
  std::array<std::uint8_t, kMaxMacPayload> payload{};
  const std::size_t n = set_mac_payload(set, guard.scene(), payload);
  hil::LinkEnvelope e = guard.protect(std::span<const std::uint8_t>(payload.data(), n));
  if (!guard.authenticated()) e.mac = unkeyed_mac(std::span<const std::uint8_t>(payload.data(), n));
  write_link_envelope(header, e);
}

hil::GuardVerdict open(std::span<const CanFrame> set, hil::LinkGuard& guard, hil::LinkEnvelope& env) {
  if (set.empty()) return guard.count(hil::GuardVerdict::kForeign);
  env = read_link_envelope(set.back());
  // The set does not carry the sender's scene hash; its MAC covers it: a set of another scene fails the MAC.
  env.scene = guard.scene();
  std::array<std::uint8_t, kMaxMacPayload> payload{};
  const std::size_t n = set_mac_payload(set, guard.scene(), payload);
  const std::span<const std::uint8_t> covered(payload.data(), n);
  const hil::GuardVerdict v = guard.check(env, covered);
  if (v != hil::GuardVerdict::kOk || guard.authenticated()) return v;
  // Without a key: a set whose body does not belong to its header (frames of two senders) is not this peer's.
  if (env.mac != unkeyed_mac(covered)) return guard.count(hil::GuardVerdict::kForeign);
  return v;
}

}  // namespace gyrostab::can
