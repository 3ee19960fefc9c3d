// `gyrostab view --lcm-url URL [--key-file KEY] [--channel-suffix S] [--scene SCENE]`: the live view of a
// plant ⇄ controller bus heard by a passive listener (lcm_listener.hpp: it never sends), served like a run's
// view (view_server.hpp: token, Host and Origin checks, nothing accepted from the page). Two channels, the
// sensor and the actuator frames, their signals named, unitised and ranged by the device's signal table; the
// controller's status word and safe state from the actuator frames' headers; the session, the authentication
// and the refusals. The device is the scene's (--scene, which also gives the run's length, its limits and its
// tick) or, without one, the one whose frame type the first frame carries (its LCM type fingerprint). Runs until
// SIGINT/SIGTERM (or --idle-exit S), then prints what it heard as one JSON line on stdout. Docs: docs/view.md.
#pragma once

#include <cstdint>
#include <string>

namespace gyrostab::tools::view {

struct LcmViewRequest {
  std::string url;
  std::string key_file;
  std::string channel_suffix;
  bool suffix_given{false};
  std::string scene_path;
  std::int64_t ticks{-1};     // with --scene: the run's length if not the scene's duration
  std::string view_address;   // "" = 127.0.0.1 on a free port
  double idle_exit_s{-1};     // > 0: exit once frames came and none for this long
};

// Exit code: 0 stopped by a signal or idle, 2 bad options (refused before listening), 3 cannot listen or serve.
int run_lcm_view(const LcmViewRequest& req);

}  // namespace gyrostab::tools::view
