// The plant and controller processes of the two-process LCM mode as two threads of the test process, joined
// by the in-memory bus (hil/link/memory_bus.hpp) instead of LCM: the same loops (tools/run/plant_process.cpp,
// controller_process.cpp), codec and checks, without a network. For the allocation test (the hooks run behind
// a two-thread barrier, so one snapshot covers both loops from their first tick to their last) and the
// lockstep determinism test.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "hil/link/memory_bus.hpp"
#include "tools/commands.hpp"

namespace gyrostab::testing {

struct PairResult {
  int plant_rc{-1}, controller_rc{-1};
  nlohmann::json plant_report, controller_report;
  std::string csv;
};

// Runs `scene` for `ticks` ticks with the plant in one thread and the controller in another. `hook_before`
// and `hook_after` (may be null) are installed as both requests' before_loop / after_loop. `lcm_suffix`
// non-empty: over LCM's default udpm:// URL with this channel suffix (needs a multicast route) instead of the
// in-memory bus.
inline PairResult run_pair_in_threads(const std::string& scene, std::int64_t ticks,
                                      void (*hook_before)() = nullptr, void (*hook_after)() = nullptr,
                                      const std::string& lcm_suffix = "") {
  auto bus = std::make_unique<hil::MemoryBus>();
  PairResult r;
  tools::RunRequest plant, controller;
  for (tools::RunRequest* q : {&plant, &controller}) {
    q->scene_path = scene;
    q->ticks = ticks;
    q->write_outputs = false;
    q->progress = false;
    if (lcm_suffix.empty()) {
      q->transport.memory_bus = bus.get();
    } else {
      q->transport.channel_suffix = lcm_suffix;
    }
    q->before_loop = hook_before;
    q->after_loop = hook_after;
  }
  plant.role = tools::Role::kPlant;
  plant.report_out = &r.plant_report;
  plant.csv_out = &r.csv;
  controller.role = tools::Role::kController;
  controller.report_out = &r.controller_report;
  std::thread c([&] { r.controller_rc = tools::run_scene(controller); });
  r.plant_rc = tools::run_scene(plant);
  c.join();
  return r;
}

// A barrier for the two loops' hooks: the second thread to arrive runs `at_meeting`, then both go on.
class TwoThreadBarrier {
 public:
  template <class F>
  void meet(F&& at_meeting) {
    std::unique_lock<std::mutex> lock(m_);
    const int gen = generation_;
    if (++arrived_ == 2) {
      at_meeting();
      arrived_ = 0;
      ++generation_;
      cv_.notify_all();
    } else {
      cv_.wait(lock, [&] { return generation_ != gen; });
    }
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int arrived_{0};
  int generation_{0};
};

}  // namespace gyrostab::testing
