// report.json blocks of a plant or controller process: the link counters ("link") and the timing
// statistics ("timing" additions), see docs/transport.md.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "hil/can/frame_codec.hpp"
#include "hil/link/link_counters.hpp"
#include "hil/rt/latency_histogram.hpp"
#include "hil/link/link_guard.hpp"
#include "hil/link/source_watch.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/scene/scene_hash.hpp"
#include "tools/run/link_settings.hpp"
#include "tools/run/link_stats.hpp"

namespace gyrostab::tools {

inline nlohmann::json histogram_json(const hil::LatencyHistogram& h) {
  return {{"samples", h.count()},          {"min_ns", h.min_ns()}, {"p50_ns", h.quantile_ns(0.50)},
          {"p99_ns", h.quantile_ns(0.99)}, {"max_ns", h.max_ns()}, {"mean_ns", h.mean_ns()}};
}

inline nlohmann::json counters_json(const hil::LinkCounters& c) {
  return {{"sent", c.sent},
          {"send_errors", c.send_errors},
          {"resent", c.resent},
          {"dropped_by_fault", c.dropped_by_fault},
          {"corrupted_by_fault", c.corrupted_by_fault},
          {"lost_by_fault", c.lost_by_fault},
          {"received", c.received},
          {"accepted", c.accepted},
          {"rejected",
           {{"total", c.rejected()},
            {"size", c.rejected_size},
            {"fingerprint", c.rejected_fingerprint},
            {"malformed", c.rejected_malformed},
            {"non_finite", c.rejected_non_finite},
            {"out_of_range", c.rejected_out_of_range},
            {"stale", c.rejected_stale},
            {"repeated", c.rejected_repeated},
            {"ahead", c.rejected_ahead},
            {"sequence_jump", c.rejected_jump},
            {"before_handshake", c.rejected_before_handshake}}},
          {"missed_frames", c.missed_frames},
          {"timeouts", c.timeouts},
          {"resynced", c.resynced}};
}

// What a run found hijacked says (both ends, docs/protocol.md "A second source on the bus"): whom the second
// source speaks as, its evidence — `frames` named as "sensor frames" or "commands" — and what this end did.
inline std::string hijack_message(const char* as_whom, std::uint64_t peer, bool by_stale_run, std::int64_t tick,
                                  const char* frames, const char* what_was_done) {
  return std::string("hijacked: a second source sends as ") + as_whom + " " + format_link_id(peer) +
         (by_stale_run ? " (stale frames contradicting the accepted ones on " +
                             std::to_string(hil::SourceWatch::kStaleTicks) + " ticks in a row up to tick " +
                             std::to_string(tick) + ")"
                       : std::string(" (two different ") + frames + " for tick " + std::to_string(tick) + ")") +
         "; " + what_was_done + " (without a link key anyone who reads the bus can copy the ids: use --key-file)";
}

// report.json link.session of a guard: who this end was, whom it bound to, and what the guard refused.
inline nlohmann::json session_json(const hil::LinkGuard& g) {
  const hil::GuardCounters& c = g.counters();
  nlohmann::json j = {
      {"session", format_link_id(g.session())},
      {"own_id", format_link_id(g.own_sender())},
      {"peer", g.bound() ? nlohmann::json(format_link_id(g.peer())) : nlohmann::json(nullptr)},
      {"scene", g.scene() != 0 ? nlohmann::json(format_scene_hash(g.scene())) : nlohmann::json(nullptr)},
      {"authenticated", g.authenticated()},
      {"refused",
       {{"recorded", c.recorded},
        {"foreign", c.foreign},
        {"bad_mac", c.bad_mac},
        {"replayed", c.replayed},
        {"other_scene", c.other_scene}}}};
  if (c.other_scene > 0) j["other_scene"] = format_scene_hash(c.last_other_scene);
  return j;
}

// report.json link.session: who this end was, whom it bound to, and what the guard refused.
template <class Endpoint>
nlohmann::json session_json(const Endpoint& ep) {
  return session_json(ep.guard());
}

// Appended to "peer lost": a peer that falls silent while frames of other senders arrive is most likely
// drowned by another pair (on CAN the two pairs' frames share identifiers, so their alive counters interleave
// and few sets complete) or by a log played onto the link. The exit code stays 6 (the run did not complete);
// the message names the likely cause.
template <class Endpoint>
std::string refused_hint(const Endpoint& ep) {
  std::string hint;
  const hil::GuardCounters& g = ep.guard().counters();
  if (g.other_scene > 0)
    hint += "; " + std::to_string(g.other_scene) + " frames came from an end running another scene (its hash " +
            format_scene_hash(g.last_other_scene) + ", ours " + format_scene_hash(ep.guard().scene()) + ")";
  if (const std::uint64_t refused = g.rejected() - g.other_scene; refused > 0)
    hint += "; " + std::to_string(refused) + " frames on the link were not this session's or failed its authentication";
  if constexpr (requires { ep.sensor_counters(); }) {
    std::uint64_t out_of_sequence = 0;
    for (const auto* c : {&ep.sensor_counters(), &ep.actuator_counters()})
      out_of_sequence += c->count(can::FrameError::kCounterSkipped) + c->count(can::FrameError::kCounterRepeated);
    if (out_of_sequence > 0)
      hint += "; " + std::to_string(out_of_sequence) + " CAN frames had alive counters out of sequence";
  }
  return hint.empty() ? hint : hint + " (another pair or a played log on this link?)";
}

// The exit code of a process whose loop completed: 0, or kExitForeignFrames when the link carried frames that
// were not this session's or failed its authentication — the results stand (none was acted on), but the link
// was shared, replayed onto or attacked, and the exit code says so (with one line on stderr).
// `peer_refused`: the frames the other end of the link refused for the same causes and reported back (the
// controller image on the target link counts them itself: report.json link.target.image_refused.foreign); they
// reach the exit code as the host's own refusals do.
inline int completed_exit_code(const char* role, const std::string& scene_name, const hil::LinkGuard& g,
                               std::uint64_t peer_refused = 0) {
  const std::uint64_t refused = g.counters().rejected();
  if (refused == 0 && peer_refused == 0) return 0;
  if (g.counters().other_scene > 0) {
    std::fprintf(stderr,
                 "gyrostab %s: %s: completed, but %llu frames came from an end running another scene (its hash %s, "
                 "ours %s); none was acted on\n",
                 role, scene_name.c_str(), static_cast<unsigned long long>(g.counters().other_scene),
                 format_scene_hash(g.counters().last_other_scene).c_str(), format_scene_hash(g.scene()).c_str());
  }
  if (refused > g.counters().other_scene) {
    std::fprintf(stderr,
                 "gyrostab %s: %s: completed, but %llu frames on the link were not this session's or failed its "
                 "authentication (report.json link.session.refused); none was acted on\n",
                 role, scene_name.c_str(), static_cast<unsigned long long>(refused - g.counters().other_scene));
  }
  if (peer_refused > 0) {
    std::fprintf(stderr,
                 "gyrostab %s: %s: completed, but the controller image refused %llu frames that were not this "
                 "session's (report.json link.target.image_refused.foreign); none was acted on\n",
                 role, scene_name.c_str(), static_cast<unsigned long long>(peer_refused));
  }
  return kExitForeignFrames;
}

inline nlohmann::json link_timing_json(const LinkStats& s, const LinkSettings& settings) {
  nlohmann::json t{{"mode", settings.real_time ? "real_time" : "lockstep"},
                   {"period_target_ns", settings.period_ns},
                   {"period_ns", histogram_json(s.period)},
                   {"compute_ns", histogram_json(s.compute)},
                   {"overruns", s.overruns}};
  if (settings.real_time) {
    t["jitter_ns"] = histogram_json(s.jitter);
    if (s.lateness.count() > 0) t["lateness_ns"] = histogram_json(s.lateness);
  }
  if (s.round_trip.count() > 0) t["round_trip_ns"] = histogram_json(s.round_trip);
  return t;
}

}  // namespace gyrostab::tools
