// What one end of a plant ⇄ controller link counts (docs/architecture.md, messages and transports: bad
// input is counted, reported and handled,
// never applied). Transport-independent: the LCM link and the in-memory test link fill the same struct, and
// the run report prints it (tools/run/link_report.hpp). Plain counters, no heap.
#pragma once

#include <cstdint>

namespace gyrostab::hil {

struct LinkCounters {
  // Sending side.
  std::uint64_t sent{0};                // frames published [-]
  std::uint64_t send_errors{0};         // publishes the transport refused [-]
  std::uint64_t resent{0};              // lockstep: frames published again because no answer came [-]
  std::uint64_t dropped_by_fault{0};    // frames withheld by --drop-frames (fault injection) [-]
  std::uint64_t lost_by_fault{0};       // frames lost on the way by --loss (fault injection) [-]
  std::uint64_t corrupted_by_fault{0};  // frames sent with a NaN by --corrupt-frames (fault injection) [-]
  // Receiving side: every message on the receive channel is `received`, then exactly one of accepted or a
  // rejection reason (checked in this order).
  std::uint64_t received{0};
  std::uint64_t accepted{0};
  std::uint64_t rejected_size{0};          // length is not the type's encoded size (incl. oversize) [-]
  std::uint64_t rejected_fingerprint{0};   // not this type (LCM fingerprint) [-]
  std::uint64_t rejected_malformed{0};     // the decoder refused the body [-]
  std::uint64_t rejected_non_finite{0};    // actuator frame with NaN/Inf (plant side) [-]
  std::uint64_t rejected_out_of_range{0};  // actuator command outside the scene's limits (plant side) [-]
  std::uint64_t rejected_stale{0};         // tick or sequence older than expected [-]
  std::uint64_t rejected_repeated{0};      // exact repeat of the last accepted frame (tick and sequence) [-]
  std::uint64_t rejected_ahead{0};         // tick further ahead than the link allows [-]
  std::uint64_t rejected_jump{0};          // sequence jumped further than the ticks since the last frame [-]
  std::uint64_t rejected_before_handshake{0};  // controller: a frame of a session before its handshake [-]
  // Per tick.
  std::uint64_t missed_frames{0};  // ticks that ended without an accepted frame [-]
  std::uint64_t timeouts{0};       // waits that reached their deadline [-]
  std::uint64_t resynced{0};       // real time: late frames the controller re-phased its deadlines on [-]

  std::uint64_t rejected() const {
    return rejected_size + rejected_fingerprint + rejected_malformed + rejected_non_finite +
           rejected_out_of_range + rejected_stale + rejected_repeated + rejected_ahead + rejected_jump +
           rejected_before_handshake;
  }
};

}  // namespace gyrostab::hil
