#include "tools/view/view_store.hpp"

#include <algorithm>
#include <cmath>

#include "tools/log/signal_channel.hpp"

namespace gyrostab::tools::view {

ViewStore::ViewStore(std::int64_t total_ticks, int every, std::size_t width)
    : total_ticks_(std::max<std::int64_t>(total_ticks, 1)), width_(width) {
  const std::int64_t rows = total_ticks_ / std::max(every, 1) + 1;
  buckets_ = std::clamp<std::int64_t>(rows, 1, kMaxBuckets);
  const std::size_t n = static_cast<std::size_t>(buckets_);
  const std::size_t signals = width_ > 0 ? width_ - 1 : 0;
  b_.resize(n);
  lo_.assign(n * signals, 0.0);
  hi_.assign(n * signals, 0.0);
  lo_first_.assign(n * signals, 0);
  last_values_.assign(width_, 0.0);
}

std::int64_t ViewStore::bucket_of(std::int64_t tick) const {
  if (tick <= 0) return 0;
  // In doubles, as the page's test computes it (tests/browser/view_page_test.mjs).
  const auto b = static_cast<std::int64_t>(
      std::floor(static_cast<double>(tick) * static_cast<double>(buckets_) / static_cast<double>(total_ticks_ + 1)));
  return std::min(b, buckets_ - 1);
}

void ViewStore::add(const RowHeader& h, const double* v) {
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
