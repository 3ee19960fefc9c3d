#include "tools/view/view_store.hpp"

#include <algorithm>
#include <cmath>

#include "tools/log/signal_channel.hpp"

namespace gyrostab::tools::view {

ViewStore::ViewStore(std::int64_t total_ticks, int every, std::size_t width, bool growable)
    : width_(width), growable_(growable) {
  if (growable) {
    buckets_ = kMaxBuckets;
    total_ticks_ = std::max<std::int64_t>(total_ticks, kMaxBuckets * std::max(every, 1) - 1);
  } else {
    total_ticks_ = std::max<std::int64_t>(total_ticks, 1);
    const std::int64_t rows = total_ticks_ / std::max(every, 1) + 1;
    buckets_ = std::clamp<std::int64_t>(rows, 1, kMaxBuckets);
  }
  initial_ticks_ = total_ticks_;
  const std::size_t n = static_cast<std::size_t>(buckets_);
  const std::size_t signals = width_ > 0 ? width_ - 1 : 0;
  b_.resize(n);
  lo_.assign(n * signals, 0.0);
  hi_.assign(n * signals, 0.0);
  lo_first_.assign(n * signals, 0);
  last_values_.assign(width_, 0.0);
}

void ViewStore::clear() {
  std::fill(b_.begin(), b_.end(), Bucket{});
  total_ticks_ = initial_ticks_;
  rows_ = 0;
  last_bucket_ = -1;
  last_header_ = RowHeader{};
  std::fill(last_values_.begin(), last_values_.end(), 0.0);
  status_seen_ = 0;
  safe_rows_ = 0;
}

void ViewStore::grow() {
  // (total + 1) doubles, so bucket i of the new span is exactly buckets 2i and 2i + 1 of the old one:
  // floor(tick·B / 2(T + 1)) = floor(floor(tick·B / (T + 1)) / 2).
  const std::size_t signals = width_ > 0 ? width_ - 1 : 0;
  const std::size_t half = static_cast<std::size_t>(buckets_) / 2;
  for (std::size_t i = 0; i < half; ++i) {
    const std::size_t a = 2 * i, c = 2 * i + 1;
    const Bucket ba = b_[a], bc = b_[c];
    Bucket out;
    out.n = ba.n + bc.n;
    out.t0 = ba.n > 0 ? ba.t0 : bc.t0;
    out.t1 = bc.n > 0 ? bc.t1 : ba.t1;
    for (std::size_t j = 0; j < signals; ++j) {
      double lo = lo_[a * signals + j], hi = hi_[a * signals + j];
      std::uint8_t first = lo_first_[a * signals + j];
      bool lo_late = false, hi_late = false;  // the extreme comes from the later bucket
      if (ba.n == 0) {
        lo = lo_[c * signals + j];
        hi = hi_[c * signals + j];
        first = lo_first_[c * signals + j];
      } else if (bc.n > 0) {
        const double l2 = lo_[c * signals + j], h2 = hi_[c * signals + j];
        if (l2 < lo || (std::isnan(lo) && !std::isnan(l2))) {
          lo = l2;
          lo_late = true;
        }
        if (h2 > hi || (std::isnan(hi) && !std::isnan(h2))) {
          hi = h2;
          hi_late = true;
        }
        if (lo_late && hi_late) first = lo_first_[c * signals + j];
        else if (lo_late) first = 0;
        else if (hi_late) first = 1;
      }
      lo_[i * signals + j] = lo;
      hi_[i * signals + j] = hi;
      lo_first_[i * signals + j] = first;
    }
    b_[i] = out;
  }
  for (std::size_t i = half; i < static_cast<std::size_t>(buckets_); ++i) b_[i] = Bucket{};
  total_ticks_ = 2 * total_ticks_ + 1;
  last_bucket_ = last_bucket_ < 0 ? -1 : last_bucket_ / 2;
}

std::int64_t ViewStore::bucket_of(std::int64_t tick) const {
  if (tick <= 0) return 0;
  // In doubles, as the page's test computes it (tests/browser/view_page_test.mjs).
  const auto b = static_cast<std::int64_t>(
      std::floor(static_cast<double>(tick) * static_cast<double>(buckets_) / static_cast<double>(total_ticks_ + 1)));
  return std::min(b, buckets_ - 1);
}

bool ViewStore::add(const RowHeader& h, const double* v) {
  bool grew = false;
  while (growable_ && h.tick > total_ticks_ && total_ticks_ < (std::int64_t{1} << 61)) {
    grow();
    grew = true;
  }
  const std::int64_t i = bucket_of(h.tick);
  Bucket& b = b_[static_cast<std::size_t>(i)];
  const std::size_t signals = width_ > 0 ? width_ - 1 : 0;
  double* lo = &lo_[static_cast<std::size_t>(i) * signals];
  double* hi = &hi_[static_cast<std::size_t>(i) * signals];
  std::uint8_t* first = &lo_first_[static_cast<std::size_t>(i) * signals];
  const double t = width_ > 0 ? v[0] : 0.0;
  if (b.n == 0) {
    b.t0 = t;
    for (std::size_t j = 0; j < signals; ++j) {
      lo[j] = hi[j] = v[j + 1];
      first[j] = 1;
    }
  } else {
    for (std::size_t j = 0; j < signals; ++j) {
      const double x = v[j + 1];
      // NaN never replaces a finite extreme; a finite value replaces a NaN one.
      if (x < lo[j] || (std::isnan(lo[j]) && !std::isnan(x))) {
        lo[j] = x;
        first[j] = 0;  // the minimum is now the later of the two
      }
      if (x > hi[j] || (std::isnan(hi[j]) && !std::isnan(x))) {
        hi[j] = x;
        first[j] = 1;
      }
    }
  }
  b.t1 = t;
  ++b.n;
  ++rows_;
  last_bucket_ = std::max(last_bucket_, i);
  last_header_ = h;
  std::copy(v, v + width_, last_values_.begin());
  status_seen_ |= h.status;
  if ((h.flags & kSafe) != 0) ++safe_rows_;
  return grew;
}

namespace {
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json ViewStore::buckets_json(std::int64_t from) const {
  nlohmann::json out = nlohmann::json::array();
  const std::size_t signals = width_ > 0 ? width_ - 1 : 0;
  for (std::int64_t i = std::max<std::int64_t>(from, 0); i <= last_bucket_; ++i) {
    const Bucket& b = b_[static_cast<std::size_t>(i)];
    if (b.n == 0) continue;
    nlohmann::json lo = nlohmann::json::array(), hi = nlohmann::json::array(), first = nlohmann::json::array();
    for (std::size_t j = 0; j < signals; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * signals + j;
      lo.push_back(number(lo_[k]));
      hi.push_back(number(hi_[k]));
      first.push_back(lo_first_[k]);
    }
    out.push_back({{"i", i}, {"t0", b.t0}, {"t1", b.t1}, {"n", b.n}, {"lo", lo}, {"hi", hi}, {"lo_first", first}});
  }
  return out;
}

}  // namespace gyrostab::tools::view
