// What every end of a plant ⇄ controller link keeps beside its transport, whatever the transport (LCM and the
// memory bus: frame_endpoint.hpp; CAN: hil/can/can_endpoint.hpp; the emulated target:
// hil/target/target_endpoint.hpp): the link guard (session, peer, MAC), the link counters, and the --loss fault
// injection with its own seeded stream (a rerun loses the same transmissions in the same order). No heap.
#pragma once

#include <cstdint>

#include "hil/link/link_counters.hpp"
#include "hil/link/link_guard.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::hil {

class EndpointBook {
 public:
  explicit EndpointBook(const GuardConfig& guard) : guard_(guard) {}

  const LinkGuard& guard() const { return guard_; }
  LinkCounters& counters() { return counters_; }
  const LinkCounters& counters() const { return counters_; }

  // Fault injection (--loss): every transmission this end makes, resends included, is lost on the way with
  // probability p.
  void inject_loss(double p, std::uint64_t seed, std::uint64_t stream) {
    loss_ = p;
    loss_rng_ = random::SeededRng(seed, stream);
  }

 protected:
  // Draws whether this transmission is lost on the way (counted as lost_by_fault: the sender cannot tell).
  bool lost_on_the_way() {
    if (loss_ > 0.0 && loss_rng_.uniform() < loss_) {
      ++counters_.lost_by_fault;
      return true;
    }
    return false;
  }

  LinkGuard guard_;
  LinkCounters counters_{};

 private:
  double loss_{0.0};
  random::SeededRng loss_rng_{0};
};

}  // namespace gyrostab::hil
