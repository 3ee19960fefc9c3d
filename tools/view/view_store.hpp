// What the page draws, kept by the view's server thread: the run's span [0, ticks] cut into at most
// kMaxBuckets buckets of equal ticks (about one per pixel of a wide chart); each bucket holds, per signal, the
// minimum and the maximum of its rows and which came first, so a chart of a three-hour run still shows every
// peak (a min/max envelope, not one sample in a hundred). A run with fewer rows than buckets keeps one row a
// bucket: its values exactly. Rows come from the ring in tick order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "tools/view/live_ring.hpp"

namespace gyrostab::tools::view {

inline constexpr std::int64_t kMaxBuckets = 2000;

class ViewStore {
 public:
  // `total_ticks` the run's length, `every` the recorder's row interval, `width` values per row ("t_s" first).
  // A growable store (a bus whose run's length is not known) always has kMaxBuckets buckets and doubles its span
  // (merging neighbouring buckets, which keeps every extreme) whenever a row lies past it.
  ViewStore(std::int64_t total_ticks, int every, std::size_t width, bool growable = false);

  std::int64_t buckets() const { return buckets_; }
  std::int64_t span_ticks() const { return total_ticks_; }
  // The bucket of a row at `tick`: floor(tick × buckets / (total_ticks + 1)), in doubles.
  std::int64_t bucket_of(std::int64_t tick) const;

  // Adds a row; true if the span grew to take it (every bucket changed: pages need the whole store again).
  bool add(const RowHeader& h, const double* values);
  // Forgets every row (a new run on the bus), keeping the span it started with.
  void clear();

  std::int64_t rows() const { return rows_; }
  std::int64_t last_bucket() const { return last_bucket_; }  // -1 before the first row
  const RowHeader& last_header() const { return last_header_; }
  const std::vector<double>& last_values() const { return last_values_; }
  std::uint32_t status_seen() const { return status_seen_; }  // every status bit that was ever set
  std::int64_t safe_rows() const { return safe_rows_; }

  // Buckets [from, last_bucket()] as JSON: [{"i", "t0", "t1", "n", "lo": [...], "hi": [...], "lo_first": [0|1...]}]
  // ("t_s" is not repeated in lo/hi: index j of lo is signal j + 1).
  nlohmann::json buckets_json(std::int64_t from) const;

 private:
  struct Bucket {
    double t0{0}, t1{0};
    std::int64_t n{0};
  };
  void grow();
  std::int64_t initial_ticks_;
  std::int64_t total_ticks_;
  std::int64_t buckets_;
  std::size_t width_;
  bool growable_;
  std::vector<Bucket> b_;
  std::vector<double> lo_, hi_;
  std::vector<std::uint8_t> lo_first_;
  std::int64_t rows_{0};
  std::int64_t last_bucket_{-1};
  RowHeader last_header_{};
  std::vector<double> last_values_;
  std::uint32_t status_seen_{0};
  std::int64_t safe_rows_{0};
};

}  // namespace gyrostab::tools::view
