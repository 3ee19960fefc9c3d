// Records the main signals of a run into a table sized before the loop starts (no allocation per tick),
// then writes it as CSV. Every `every`-th tick is one row: tick time plus the device's columns — all of
// them, or only those the scene's `[output] signals` names (check_signals() refuses an unknown name with
// the list of valid ones). With a selection the device still writes its full row (into a scratch row); the
// table keeps the selected columns only, so memory and CSV size follow what the scene asks for.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gyrostab::tools {

// What a run may record: the table is sized before tick 0, so its memory is known before anything runs, and
// a scene (or a --ticks) that would need more than the ceiling is refused by `check` and `run` alike with the
// size it would need. A CSV beyond the warning size is written, with a warning first.
inline constexpr std::int64_t kRecorderCeilingBytes = std::int64_t{1} << 30;  // 1 GiB of table
inline constexpr std::int64_t kCsvWarningBytes = 200'000'000;                 // 200 MB of CSV
inline constexpr std::int64_t kCsvBytesPerValue = 20;  // "%.17g," of a typical signal (measured: 19-24)

struct RecordingSize {
  std::int64_t rows{0};
  std::int64_t columns{0};  // recorded ones, t_s included
  std::int64_t table_bytes{0};
  std::int64_t csv_bytes_estimate{0};
  bool overflow{false};  // more than an int64 of bytes: refused like an oversized table
};
// The size of a recording of `ticks` ticks, one row every `every`, of `columns` columns (besides t_s).
RecordingSize recording_size(std::int64_t ticks, int every, std::size_t columns);
// "" if `size` is within the ceiling, else why not, with what would help.
std::string recording_problem(const RecordingSize& size);
// "" or the warning about the CSV's size.
std::string recording_warning(const RecordingSize& size);

class Recorder {
 public:
  // `selection`: the column names to keep, in the CSV in this order; empty = every column.
  Recorder(std::vector<std::string> columns, std::int64_t ticks, int every,
           const std::vector<std::string>& selection = {});

  // "" if every name in `wanted` is one of `columns` (and none is listed twice), else the message naming the
  // offending name and the valid ones.
  static std::string check_signals(const std::vector<std::string>& columns, const std::vector<std::string>& wanted);

  // Whether `tick` gets a row (tick a multiple of `every`). Asked once per tick in order, it compares with the
  // next multiple instead of dividing; a caller that skips ticks still gets the multiples.
  bool due(std::int64_t tick) {
    if (tick < next_due_) return false;
    if (tick == next_due_) {
      next_due_ += every_;
      return true;
    }
    next_due_ = (tick / every_ + 1) * every_;
    return tick % every_ == 0;
  }
  // Pointer to the next row's columns (after the time column), all of the device's columns in order;
  // nullptr when the table is full.
  double* row(double t) {
    if (rows_ >= capacity_) return nullptr;
    flush();
    double* r = data_.data() + rows_ * width_;
    r[0] = t;
    ++rows_;
    if (pick_.empty()) return r + 1;
    pending_ = true;
    return scratch_.data();
  }

  // The last row of the table ("t_s" first, the recorded columns), complete; nullptr before the first.
  const double* last_row() const {
    if (rows_ == 0) return nullptr;
    flush();
    return data_.data() + (rows_ - 1) * width_;
  }

  std::size_t rows() const { return static_cast<std::size_t>(rows_); }
  std::size_t width() const { return static_cast<std::size_t>(width_); }
  const std::vector<std::string>& columns() const { return columns_; }  // recorded ones, "t_s" first
  double at(std::size_t row, std::size_t col) const {
    flush();
    return data_[row * static_cast<std::size_t>(width_) + col];
  }

  bool write_csv(const std::string& path, std::string& error) const;
  std::string csv() const;

 private:
  // Moves the selected columns of the last scratch row into the table.
  void flush() const {
    if (!pending_) return;
    double* r = data_.data() + (rows_ - 1) * width_ + 1;
    for (std::size_t j = 0; j < pick_.size(); ++j) r[j] = scratch_[pick_[j]];
    pending_ = false;
  }

  std::vector<std::string> columns_;  // including "t_s"
  int every_;
  std::int64_t next_due_;  // the next multiple of every_ to record
  std::int64_t width_;
  std::int64_t capacity_;
  std::int64_t rows_{0};
  std::vector<std::size_t> pick_;   // device column index of each recorded column; empty: all
  std::vector<double> scratch_;     // the device's full row when selecting
  mutable std::vector<double> data_;
  mutable bool pending_{false};
};

}  // namespace gyrostab::tools
