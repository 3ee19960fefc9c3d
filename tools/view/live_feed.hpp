// What the loop hands the live view: the loop's RowSink (closed_loop.hpp). After the recorder took a row, the
// loop passes it here; the feed adds the controller's status word and safe flag when the controller runs in
// this process and pushes the whole into the ring (live_ring.hpp). It reads, never writes, the loop's state,
// so a run with a view computes the same bits as one without (tests/determinism/view_determinism_test.cpp).
#pragma once

#include "tools/loop/closed_loop.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/view/live_ring.hpp"

namespace gyrostab::tools::view {

class LiveFeed final : public RowSink {
 public:
  LiveFeed(LiveRing& ring, const ControllerPort* controller) : ring_(ring), controller_(controller) {}
  void row(std::int64_t tick, const double* values) override {
    RowHeader h;
    h.tick = tick;
    if (controller_ != nullptr) {
      h.status = controller_->monitor_status();
      h.flags = kHasStatus | (controller_->in_safe_state() ? kSafe : 0u);
    }
    ring_.push(h, values);
  }

 private:
  LiveRing& ring_;
  const ControllerPort* controller_;
};

}  // namespace gyrostab::tools::view
