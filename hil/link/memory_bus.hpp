// An in-process stand-in for the LCM bus (tests): two directions (plant → controller, controller → plant),
// each a bounded queue of whole messages in storage allocated at construction, guarded by a mutex and a
// condition variable. The plant and the controller loops run in two threads of one process and each takes one
// end (MemoryTransport). Nothing allocates after construction, so a test can count the loops' allocations
// with the transport in place (tests/alloc/lcm_loop_alloc_test.cpp). Messages are the codec's wire bytes, the
// same as over LCM, so the decoders and checks run as they do over the network.
#pragma once

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <mutex>

#include "hil/link/frame_transport.hpp"

namespace gyrostab::hil {

class MemoryQueue {
 public:
  static constexpr int kCapacity = 64;  // messages in flight per direction; a full queue drops the newest

  bool push(const std::uint8_t* data, int size) {
    if (size < 0 || size > kMaxMessageBytes) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (count_ == kCapacity) return false;
      Slot& s = slots_[static_cast<std::size_t>((head_ + count_) % kCapacity)];
      std::memcpy(s.bytes.data(), data, static_cast<std::size_t>(size));
      s.size = size;
      ++count_;
    }
    cv_.notify_one();
    return true;
  }

  // Copies the oldest message into `out` (kMaxMessageBytes) and returns its size, or -1 at the deadline.
  int pop(std::uint8_t* out, std::int64_t deadline_ns) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto ready = [this] { return count_ > 0; };
    if (deadline_ns == kNoDeadline) {
      cv_.wait(lock, ready);
    } else {
      // std::chrono::steady_clock is CLOCK_MONOTONIC on Linux (libstdc++), the clock of deadline_ns.
      const auto until = std::chrono::steady_clock::time_point(std::chrono::nanoseconds(deadline_ns));
      // An empty queue past its deadline answers at once: wait_until would still enter the kernel (a futex
      // wait with an expired timeout), which took 92 % of the link guard fuzzer's time.
      if (!ready() && std::chrono::steady_clock::now() >= until) return -1;
      if (!cv_.wait_until(lock, until, ready)) return -1;
    }
    Slot& s = slots_[static_cast<std::size_t>(head_)];
    std::memcpy(out, s.bytes.data(), static_cast<std::size_t>(s.size));
    head_ = (head_ + 1) % kCapacity;
    --count_;
    return s.size;
  }

 private:
  struct Slot {
    std::array<std::uint8_t, kMaxMessageBytes> bytes{};
    int size{0};
  };
  std::mutex mutex_;
  std::condition_variable cv_;
  std::array<Slot, kCapacity> slots_{};
  int head_{0};
  int count_{0};
};

struct MemoryBus {
  MemoryQueue to_controller;  // sensor frames
  MemoryQueue to_plant;       // actuator frames
};

// One end of a MemoryBus (the frame_transport.hpp concept).
class MemoryTransport {
 public:
  MemoryTransport(MemoryQueue& tx, MemoryQueue& rx) : tx_(tx), rx_(rx) {}

  bool publish(const std::uint8_t* data, int size) { return tx_.push(data, size); }

  RxStatus receive(std::int64_t deadline_ns, Message& out) {
    const int n = rx_.pop(buffer_.data(), deadline_ns);
    if (n < 0) return RxStatus::kTimeout;
    out.data = buffer_.data();
    out.size = n;
    return RxStatus::kMessage;
  }

 private:
  MemoryQueue& tx_;
  MemoryQueue& rx_;
  std::array<std::uint8_t, kMaxMessageBytes> buffer_{};
};

}  // namespace gyrostab::hil
