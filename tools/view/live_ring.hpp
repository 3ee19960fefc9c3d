// The live view's single-producer/single-consumer ring: the loop thread pushes each recorded row (its tick,
// the controller's status word and safe flag, the row's values), the view's server thread drains it. Every
// slot is allocated by the constructor; push() never blocks, never allocates, and when the ring is full it
// drops the row and counts it on the producer's side (the loop goes on; the page shows the count).
// Head and tail live on cache lines of their own; each side keeps a copy of the other's index and reads the
// shared one only when its copy says the ring is full (producer) or empty (consumer).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace gyrostab::tools::view {

struct RowHeader {
  std::int64_t tick{0};
  std::uint32_t status{0};  // the controller's fault-monitor status word (msg/fault_bits.hpp)
  std::uint32_t flags{0};   // kHasStatus, kSafe, kAuthenticated, kNewRun
};
inline constexpr std::uint32_t kHasStatus = 1u;  // status and kSafe are known (the controller runs here, or
                                                 // the row is an actuator frame, whose status word is the controller's)
inline constexpr std::uint32_t kSafe = 2u;       // the controller is in its safe state
inline constexpr std::uint32_t kAuthenticated = 4u;  // a frame whose MAC verified under the viewer's key
inline constexpr std::uint32_t kNewRun = 8u;         // the first row of another run (a new session on the bus)

class LiveRing {
 public:
  // `width` values per row; `capacity` rows, rounded up to a power of two.
  LiveRing(std::size_t width, std::size_t capacity) : width_(width) {
    std::size_t c = 1;
    while (c < capacity) c <<= 1;
    mask_ = c - 1;
    headers_.resize(c);
    values_.resize(c * width);
  }

  std::size_t width() const { return width_; }
  std::size_t capacity() const { return mask_ + 1; }

  // Producer (the loop thread).
  bool push(const RowHeader& h, const double* values) noexcept {
    const std::uint64_t head = head_.v.load(std::memory_order_relaxed);
    if (head - tail_cache_ > mask_) {
      tail_cache_ = tail_.v.load(std::memory_order_acquire);
      if (head - tail_cache_ > mask_) {
        dropped_.v.store(dropped_.v.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        return false;
      }
    }
    const std::size_t slot = static_cast<std::size_t>(head & mask_);
    headers_[slot] = h;
    if (width_ != 0) std::memcpy(&values_[slot * width_], values, width_ * sizeof(double));
    head_.v.store(head + 1, std::memory_order_release);
    return true;
  }
  std::uint64_t dropped() const { return dropped_.v.load(std::memory_order_relaxed); }
  std::uint64_t pushed() const { return head_.v.load(std::memory_order_acquire); }

  // Consumer (the server thread): calls f(header, values) for up to `max` rows in order; the count.
  template <class F>
  std::size_t drain(F&& f, std::size_t max = static_cast<std::size_t>(-1)) {
    const std::uint64_t tail = tail_.v.load(std::memory_order_relaxed);
    if (head_cache_ == tail) head_cache_ = head_.v.load(std::memory_order_acquire);
    std::uint64_t t = tail;
    std::size_t n = 0;
    while (t != head_cache_ && n < max) {
      const std::size_t slot = static_cast<std::size_t>(t & mask_);
      f(headers_[slot], width_ != 0 ? &values_[slot * width_] : nullptr);
      ++t;
      ++n;
    }
    tail_.v.store(t, std::memory_order_release);
    return n;
  }

 private:
  struct alignas(64) Index {
    std::atomic<std::uint64_t> v{0};
  };
  std::size_t width_;
  std::size_t mask_{0};
  std::vector<RowHeader> headers_;
  std::vector<double> values_;
  Index head_;                             // written by the producer
  Index tail_;                             // written by the consumer
  Index dropped_;                          // written by the producer
  alignas(64) std::uint64_t tail_cache_{0};  // the producer's copy of tail_
  alignas(64) std::uint64_t head_cache_{0};  // the consumer's copy of head_
};

}  // namespace gyrostab::tools::view
