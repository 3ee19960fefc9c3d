// One end of a plant ⇄ controller link over any byte transport (frame_transport.hpp): encodes the frames it
// sends with the LCM codec (hil/lcm/frame_codec.hpp) into a buffer allocated with the endpoint, decodes what
// it receives into the caller's frame, and counts (link_counters.hpp). Codec-level rejections (size,
// fingerprint, malformed body) are counted here and never reach the caller; content and order checks are the
// caller's (they depend on the direction: hil/link/actuator_frame_check.hpp, the firmware fault monitor).
// No heap after construction.
#pragma once

#include <array>
#include <cstdint>

#include "hil/lcm/frame_codec.hpp"
#include "hil/link/frame_transport.hpp"
#include "hil/link/link_counters.hpp"

namespace gyrostab::hil {

template <class Transport>
class FrameEndpoint {
 public:
  explicit FrameEndpoint(Transport& transport) : transport_(transport) {}

  // Encodes and publishes `f`; the bytes are kept for resend(). false: encoding or the transport failed.
  template <class Frame>
  bool send(const Frame& f, std::int64_t sim_time_us) {
    last_size_ = encode(f, sim_time_us, tx_.data(), static_cast<int>(tx_.size()));
    if (last_size_ < 0) {
      ++counters_.send_errors;
      return false;
    }
    return publish_last();
  }

  // Publishes the last sent frame again, byte for byte (lockstep recovery of a lost datagram).
  bool resend() {
    if (last_size_ <= 0) return false;
    ++counters_.resent;
    return publish_last();
  }

  // Waits until CLOCK_MONOTONIC deadline_ns for a message that decodes as `Frame`. kMessage: `out` holds it
  // (and *sim_time_us its simulated time). Messages that do not decode are counted and skipped.
  template <class Frame>
  RxStatus receive(std::int64_t deadline_ns, Frame& out, std::int64_t* sim_time_us = nullptr) {
    for (;;) {
      Message m;
      const RxStatus s = transport_.receive(deadline_ns, m);
      if (s != RxStatus::kMessage) {
        if (s == RxStatus::kTimeout) ++counters_.timeouts;
        return s;
      }
      ++counters_.received;
      switch (decode(m.data, m.data == nullptr ? -1 : m.size, out, sim_time_us)) {
        case DecodeError::kOk:
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

  LinkCounters& counters() { return counters_; }
  const LinkCounters& counters() const { return counters_; }

 private:
  bool publish_last() {
    if (!transport_.publish(tx_.data(), last_size_)) {
      ++counters_.send_errors;
      return false;
    }
    ++counters_.sent;
    return true;
  }

  static constexpr int kTxBytes =
      kSensorEncodedSize > kActuatorEncodedSize ? kSensorEncodedSize : kActuatorEncodedSize;
  Transport& transport_;
  std::array<std::uint8_t, kTxBytes> tx_{};
  int last_size_{0};
  LinkCounters counters_{};
};

}  // namespace gyrostab::hil
