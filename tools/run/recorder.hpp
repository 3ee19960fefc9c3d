// Records the main signals of a run into a table sized before the loop starts (no allocation per tick),
// then writes it as CSV. Every `every`-th tick is one row: tick time plus the device's columns.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gyrostab::tools {

class Recorder {
 public:
  Recorder(std::vector<std::string> columns, std::int64_t ticks, int every);

  bool due(std::int64_t tick) const { return tick % every_ == 0; }
  // Pointer to the next row's columns (after the time column); nullptr when the table is full.
  double* row(double t) {
    if (rows_ >= capacity_) return nullptr;
    double* r = data_.data() + rows_ * width_;
    r[0] = t;
    ++rows_;
    return r + 1;
  }

  std::size_t rows() const { return static_cast<std::size_t>(rows_); }
  std::size_t width() const { return static_cast<std::size_t>(width_); }
  const std::vector<std::string>& columns() const { return columns_; }
  double at(std::size_t row, std::size_t col) const { return data_[row * static_cast<std::size_t>(width_) + col]; }

  bool write_csv(const std::string& path, std::string& error) const;
  std::string csv() const;

 private:
  std::vector<std::string> columns_;  // including "t_s"
  int every_;
  std::int64_t width_;
  std::int64_t capacity_;
  std::int64_t rows_{0};
  std::vector<double> data_;
};

}  // namespace gyrostab::tools
