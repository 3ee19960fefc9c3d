// Who may talk on a plant ⇄ controller link: session binding and, with a key, authentication of every frame
// (docs/transport.md, "Sessions and authentication"). Transport-independent: the LCM and in-memory links
// (frame_endpoint.hpp) put the envelope on every frame, the CAN FD link on every set, in its header frame
// (hil/can/link_seal.hpp).
//
// Envelope of every frame: the sender's id, the session id, a freshness value and a MAC.
//   - The plant draws the session id at start-up from the OS's random source (nonzero, 32 bits so that a CAN
//     frame carries it whole); its own sender id is the session id. The controller draws its sender id.
//   - The controller binds to the session of the handshake (the tick-0 sensor frame), or to the one it was
//     given (`--session`, as `gyrostab run --transport ...` passes it to both children); the plant binds to
//     the controller's sender id at the handshake (its tick-0 command). After binding, a frame of another
//     session, or of another sender on this session (a second controller, a second plant), is foreign:
//     counted, never acted on, and reported.
//   - Session 0 is never live: bus logs record it (tools/log/bus_log_writer.cpp), so a log played onto a live
//     bus (`lcm-logplayer`) is refused as "recorded".
//   - With a key (`--key-file`), every frame carries a MAC in the manner of AUTOSAR SecOC
//     (firmware/link/secoc.hpp: SipHash-2-4 over data id | session | freshness | payload): a frame whose MAC
//     does not verify, or whose freshness is not newer than the last accepted one, is rejected and counted,
//     and leaves the state as it was — a forger without the key cannot change a single command, nor lock the
//     genuine peer out. Without a key the envelope still binds the session (two pairs on one bus, a log on a
//     live bus), but a process that reads the bus can copy it.
// No heap: O(payload) per frame (one SipHash with a key, nothing without); draw_link_id() is host code.
// Test: tests/unit/link_guard_test.cpp, tests/lcm/lcm_session_test.cpp.
#pragma once

#include <sys/random.h>

#include <cstdint>
#include <optional>
#include <span>

#include "firmware/link/secoc.hpp"

namespace gyrostab::hil {

struct LinkEnvelope {
  std::uint64_t sender{0};     // the sending end's id
  std::uint64_t session{0};    // the plant's session id; 0: a recorded frame
  std::uint64_t freshness{0};  // the sender's frame counter in this direction (full 64 bits or truncated)
  std::uint64_t mac{0};        // truncated MAC; 0 without a key
  std::uint64_t scene{0};      // the sender's scene hash (tools/scene/scene_hash.hpp); covered by the MAC
};

enum class GuardVerdict : std::uint8_t {
  kOk,
  kRecorded,  // session 0: a frame of a bus log, played onto a live link
  kForeign,   // another session, or another sender on this session
  kBadMac,    // with a key: the MAC does not verify (a forgery, or a frame of another key)
  kReplayed,  // with a key: the freshness value is not newer than the last accepted one (or too far ahead)
  kOtherScene,  // this session's peer, or a would-be peer, runs another scene (its scene hash differs)
};

struct GuardCounters {
  std::uint64_t recorded{0};
  std::uint64_t foreign{0};
  std::uint64_t bad_mac{0};
  std::uint64_t replayed{0};
  std::uint64_t other_scene{0};
  std::uint64_t last_other_scene{0};  // the scene hash of the latest frame refused as another scene's
  std::uint64_t rejected() const { return recorded + foreign + bad_mac + replayed + other_scene; }
};

// What one end of a link is: its own id, the session it belongs to (0: not bound yet), the key if any, and
// the data ids of the two directions (what the MAC says a frame is for: a sensor frame cannot pass as a
// command).
struct GuardConfig {
  std::uint64_t own_sender{0};
  std::uint64_t session{0};
  std::uint64_t scene{0};  // this end's scene hash, sent in every frame; a peer's must equal it (0: not checked)
  std::uint64_t peer{0};   // the peer's sender id when known before the handshake (0: bind at the handshake)
  std::optional<firmware::link::Key128> key;
  std::uint32_t tx_data_id{0};
  std::uint32_t rx_data_id{0};
  firmware::link::SecOcProfile profile{8, 8, 1u << 16};
};

class LinkGuard {
 public:
  LinkGuard() = default;
  explicit LinkGuard(const GuardConfig& c)
      : c_(c),
        peer_(c.peer),
        sender_(c.key ? *c.key : firmware::link::Key128{}, c.tx_data_id, c.session, c.profile),
        receiver_(c.key ? *c.key : firmware::link::Key128{}, c.rx_data_id, c.session, c.profile) {}

  // The sender and session fields as this end sends them, before the MAC is computed (the MAC covers the
  // sender id, so it must stand in the frame first).
  LinkEnvelope header() const { return LinkEnvelope{c_.own_sender, c_.session, 0, 0, c_.scene}; }

  // The envelope of the next frame this end sends; `payload` is every byte of the frame the MAC covers.
  LinkEnvelope protect(std::span<const std::uint8_t> payload) {
    LinkEnvelope e{c_.own_sender, c_.session, 0, 0, c_.scene};
    if (c_.key) {
      const firmware::link::SecuredFields f = sender_.protect(payload);
      e.freshness = f.freshness;
      e.mac = f.mac;
    } else {
      e.freshness = ++plain_freshness_;
    }
    return e;
  }

  // Judges a received frame; binds nothing. kOk: the frame may be acted on (the order checks still apply).
  GuardVerdict check(const LinkEnvelope& e, std::span<const std::uint8_t> payload) {
    return count(judge(e, payload));
  }

  // Counts a refusal the transport made itself (a CAN set whose body does not belong to its header) and
  // returns it.
  GuardVerdict count(GuardVerdict v) {
    switch (v) {
      case GuardVerdict::kOk: break;
      case GuardVerdict::kRecorded: ++counters_.recorded; break;
      case GuardVerdict::kForeign: ++counters_.foreign; break;
      case GuardVerdict::kBadMac: ++counters_.bad_mac; break;
      case GuardVerdict::kReplayed: ++counters_.replayed; break;
      case GuardVerdict::kOtherScene: ++counters_.other_scene; break;
    }
    return v;
  }

  // Binds to the peer of an accepted frame (the handshake): its session if this end has none yet (the
  // controller), and its sender id. Later frames of anyone else are foreign.
  void bind(const LinkEnvelope& e) {
    if (c_.session == 0) {
      c_.session = e.session;
      sender_ = firmware::link::SecOcSender(c_.key ? *c_.key : firmware::link::Key128{}, c_.tx_data_id,
                                            c_.session, c_.profile, sender_.next_freshness());
    }
    peer_ = e.sender;
  }

  bool bound() const { return peer_ != 0; }
  std::uint64_t session() const { return c_.session; }
  std::uint64_t peer() const { return peer_; }
  std::uint64_t own_sender() const { return c_.own_sender; }
  std::uint64_t scene() const { return c_.scene; }
  bool authenticated() const { return c_.key.has_value(); }
  const GuardCounters& counters() const { return counters_; }

 private:
  GuardVerdict judge(const LinkEnvelope& e, std::span<const std::uint8_t> payload) {
    if (e.session == 0) return GuardVerdict::kRecorded;
    // No live end has id 0: binding to it would bind nobody and leave the link open to every sender.
    if (e.sender == 0) return GuardVerdict::kForeign;
    if (c_.session != 0 && e.session != c_.session) return GuardVerdict::kForeign;
    if (peer_ != 0 && e.sender != peer_) return GuardVerdict::kForeign;
    if (c_.scene != 0 && e.scene != c_.scene) {
      counters_.last_other_scene = e.scene;
      return GuardVerdict::kOtherScene;
    }
    if (!c_.key) return GuardVerdict::kOk;
    // Before the session is bound the frame is judged against the session it claims; only a frame under
    // the key verifies, whatever session it names.
    if (receiver_.session() != e.session) receiver_.rebind(e.session, 0);
    const firmware::link::Verdict v =
        receiver_.verify(payload, firmware::link::SecuredFields{e.session, e.freshness, e.mac});
    if (v == firmware::link::Verdict::kOk) return GuardVerdict::kOk;
    if (v == firmware::link::Verdict::kBadMac) return GuardVerdict::kBadMac;
    if (v == firmware::link::Verdict::kWrongSession) return GuardVerdict::kForeign;
    return GuardVerdict::kReplayed;
  }

  GuardConfig c_{};
  std::uint64_t peer_{0};
  firmware::link::SecOcSender sender_{firmware::link::Key128{}, 0, 0, firmware::link::SecOcProfile{}};
  firmware::link::SecOcReceiver receiver_{firmware::link::Key128{}, 0, 0, firmware::link::SecOcProfile{}};
  std::uint64_t plain_freshness_{0};
  GuardCounters counters_{};
};

// A nonzero 32-bit id from the OS's random source (getrandom(2)); a session id or a sender id. 0 if the
// source fails (the caller refuses to start).
inline std::uint64_t draw_link_id() {
  for (int attempt = 0; attempt < 16; ++attempt) {
    std::uint32_t v = 0;
    if (getrandom(&v, sizeof v, 0) != static_cast<ssize_t>(sizeof v)) return 0;
    if (v != 0) return v;
  }
  return 0;
}

}  // namespace gyrostab::hil
