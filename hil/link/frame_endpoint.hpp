// One end of a plant ⇄ controller link over any byte transport (frame_transport.hpp): encodes the frames it
// sends with the LCM codec (hil/lcm/frame_codec.hpp) into a buffer allocated with the endpoint, secures each
// with the link's envelope (hil/link/link_guard.hpp: sender, session, freshness, MAC with a key), decodes what
// it receives into the caller's frame, and counts (link_counters.hpp). Codec-level rejections (size,
// fingerprint, malformed body) and the guard's (recorded, foreign, bad MAC, replayed) are counted here and
// never reach the caller; content and order checks are the caller's (they depend on the direction:
// hil/link/actuator_frame_check.hpp, the firmware fault monitor). The caller binds the endpoint to its peer at
// the handshake (bind_to_last()). No heap after construction.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>

#include "hil/lcm/frame_codec.hpp"
#include "hil/link/endpoint_book.hpp"
#include "hil/link/frame_transport.hpp"
#include "hil/link/link_guard.hpp"
#include "hil/link/link_counters.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::hil {

// The guard of each end (data ids: hil/lcm/frame_codec.hpp). The plant's session is its own id, and it knows
// its controller's id when whoever started both said it (`run --transport`: 0 binds at the handshake); the
// controller has its own id and the session it was given (the plant's id, so its peer too), or 0 to bind at the
// handshake. `scene`: this end's scene hash, checked against the peer's (0: unchecked).
inline GuardConfig plant_guard(std::uint64_t session, const std::optional<firmware::link::Key128>& key,
                               std::uint64_t scene = 0, std::uint64_t controller_id = 0) {
  GuardConfig g{session, session, scene, controller_id, key, kSensorDataId, kActuatorDataId};
  return g;
}
inline GuardConfig controller_guard(std::uint64_t own_id, std::uint64_t session,
                                    const std::optional<firmware::link::Key128>& key, std::uint64_t scene = 0) {
  return GuardConfig{own_id, session, scene, session, key, kActuatorDataId, kSensorDataId};
}

template <class Transport>
class FrameEndpoint : public EndpointBook {
 public:
  FrameEndpoint(Transport& transport, const GuardConfig& guard, const msg::DeviceSignals& signals)
      : EndpointBook(guard), transport_(transport), signals_(signals) {}

  // Encodes, secures and publishes `f` (a device-independent frame, or the device's typed one); the frame's
  // bytes are kept for resend(). false: encoding or the transport failed.
  bool send(const msg::AnySensorFrame& f, std::int64_t sim_time_us) { return send_any(f, sim_time_us); }
  bool send(const msg::AnyActuatorFrame& f, std::int64_t sim_time_us) { return send_any(f, sim_time_us); }
  template <msg::TypedFrame Frame>
  bool send(const Frame& f, std::int64_t sim_time_us) {
    return send_any(msg::any_of(f), sim_time_us);
  }

  // Publishes the last sent frame again with the next freshness value (lockstep recovery of a lost datagram:
  // a byte-identical copy would be refused as a replay under a key).
  bool resend() {
    if (last_size_ <= 0) return false;
    ++counters_.resent;
    return secure_and_publish();
  }

  // Waits until CLOCK_MONOTONIC deadline_ns for a message that decodes as the frame asked for (the device's:
  // device-independent or typed). kMessage: `out` holds it (and *sim_time_us its simulated time). Messages that
  // do not decode are counted and skipped.
  RxStatus receive(std::int64_t deadline_ns, msg::AnySensorFrame& out, std::int64_t* sim_time_us = nullptr) {
    return receive_any(deadline_ns, out, sim_time_us);
  }
  RxStatus receive(std::int64_t deadline_ns, msg::AnyActuatorFrame& out, std::int64_t* sim_time_us = nullptr) {
    return receive_any(deadline_ns, out, sim_time_us);
  }
  template <msg::TypedFrame Frame>
  RxStatus receive(std::int64_t deadline_ns, Frame& out, std::int64_t* sim_time_us = nullptr) {
    decltype(msg::any_of(out)) any{};
    const RxStatus s = receive_any(deadline_ns, any, sim_time_us);
    if (s == RxStatus::kMessage) msg::from_any(any, out);
    return s;
  }

  // Binds to the peer of the frame last returned by receive() (the handshake frame).
  void bind_to_last() { guard_.bind(last_rx_); }
  // The envelope of the frame last returned by receive().
  const LinkEnvelope& last_envelope() const { return last_rx_; }
  // The device whose frames this endpoint carries.
  const msg::DeviceSignals& signals() const { return signals_; }

 private:
  template <class Frame>
  bool send_any(const Frame& f, std::int64_t sim_time_us) {
    last_size_ = encode(f, signals_, sim_time_us, tx_.data(), static_cast<int>(tx_.size()), guard_.header());
    if (last_size_ < 0) {
      ++counters_.send_errors;
      return false;
    }
    return secure_and_publish();
  }

  template <class Frame>
  RxStatus receive_any(std::int64_t deadline_ns, Frame& out, std::int64_t* sim_time_us) {
    for (;;) {
      Message m;
      const RxStatus s = transport_.receive(deadline_ns, m);
      if (s != RxStatus::kMessage) {
        if (s == RxStatus::kTimeout) ++counters_.timeouts;
        return s;
      }
      ++counters_.received;
      LinkEnvelope e;
      switch (decode(m.data, m.data == nullptr ? -1 : m.size, signals_, out, sim_time_us, &e)) {
        case DecodeError::kOk:
          if (guard_.check(e, std::span(m.data, static_cast<std::size_t>(mac_covered_bytes(m.size)))) !=
              GuardVerdict::kOk) {
            break;  // counted by the guard
          }
          last_rx_ = e;
          return RxStatus::kMessage;
        case DecodeError::kWrongSize:
          ++counters_.rejected_size;
          break;
        case DecodeError::kWrongFingerprint:
          ++counters_.rejected_fingerprint;
          break;
        case DecodeError::kMalformed:
          ++counters_.rejected_malformed;
          break;
      }
    }
  }

  bool secure_and_publish() {
    write_envelope(tx_.data(), last_size_, guard_.header());
    const LinkEnvelope e = guard_.protect(std::span<const std::uint8_t>(
        tx_.data(), static_cast<std::size_t>(mac_covered_bytes(last_size_))));
    write_envelope(tx_.data(), last_size_, e);
    return publish_last();
  }
  bool publish_last() {
    if (lost_on_the_way()) return true;
    if (!transport_.publish(tx_.data(), last_size_)) {
      ++counters_.send_errors;
      return false;
    }
    ++counters_.sent;
    return true;
  }

  static constexpr int kTxBytes = kMaxEncodedSize;
  Transport& transport_;
  const msg::DeviceSignals& signals_;
  LinkEnvelope last_rx_{};
  std::array<std::uint8_t, kTxBytes> tx_{};
  int last_size_{0};
};

}  // namespace gyrostab::hil
