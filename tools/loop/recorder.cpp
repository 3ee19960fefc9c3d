#include "tools/loop/recorder.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace gyrostab::tools {

RecordingSize recording_size(std::int64_t ticks, int every, std::size_t columns) {
  RecordingSize r;
  const std::int64_t e = every < 1 ? 1 : every;
  r.rows = (ticks < 0 ? 0 : ticks) / e + 1;
  r.columns = static_cast<std::int64_t>(columns) + 1;
  const double bytes = static_cast<double>(r.rows) * static_cast<double>(r.columns) * 8.0;
  r.overflow = bytes > 9.0e18;
  r.table_bytes = r.overflow ? INT64_MAX : r.rows * r.columns * 8;
  r.csv_bytes_estimate = r.overflow ? INT64_MAX : r.rows * r.columns * kCsvBytesPerValue;
  return r;
}

namespace {
std::string mib(std::int64_t bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g MiB", static_cast<double>(bytes) / 1048576.0);
  return buf;
}
}  // namespace

std::string recording_problem(const RecordingSize& s) {
  if (!s.overflow && s.table_bytes <= kRecorderCeilingBytes) return "";
  char buf[256];
  std::snprintf(buf, sizeof buf, "the recording would need %s (%lld rows of %lld columns), above the ceiling of %s; "
                "raise [output] record_every, name fewer [output] signals or shorten the run",
                s.overflow ? "more than 8 EiB" : mib(s.table_bytes).c_str(), static_cast<long long>(s.rows),
                static_cast<long long>(s.columns), mib(kRecorderCeilingBytes).c_str());
  return buf;
}

std::string recording_warning(const RecordingSize& s) {
  if (s.csv_bytes_estimate <= kCsvWarningBytes) return "";
  return "signals.csv will be about " + mib(s.csv_bytes_estimate) + " (" + std::to_string(s.rows) +
         " rows); [output] record_every or [output] signals make it smaller";
}

Recorder::Recorder(std::vector<std::string> columns, std::int64_t ticks, int every,
                   const std::vector<std::string>& selection)
    : every_(every < 1 ? 1 : every), next_due_(every_) {
  columns_.push_back("t_s");
  if (selection.empty() || selection == columns) {  // every column, in order: no scratch row
    for (auto& c : columns) columns_.push_back(std::move(c));
  } else {
    // Names were checked (check_signals); an unknown one here is skipped rather than recorded wrong.
    for (const std::string& want : selection) {
      const auto it = std::find(columns.begin(), columns.end(), want);
      if (it == columns.end()) continue;
      pick_.push_back(static_cast<std::size_t>(it - columns.begin()));
      columns_.push_back(want);
    }
    scratch_.assign(columns.size(), 0.0);
  }
  width_ = static_cast<std::int64_t>(columns_.size());
  capacity_ = ticks / every_ + 1;
  data_.assign(static_cast<std::size_t>(capacity_ * width_), 0.0);
}

std::string Recorder::check_signals(const std::vector<std::string>& columns, const std::vector<std::string>& wanted) {
  std::string problems;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    const std::string& w = wanted[i];
    if (std::find(columns.begin(), columns.end(), w) == columns.end()) {
      problems += (problems.empty() ? "" : "; ") + ("\"" + w + "\" is not a signal of this device");
    } else if (std::find(wanted.begin(), wanted.begin() + static_cast<std::ptrdiff_t>(i), w) !=
               wanted.begin() + static_cast<std::ptrdiff_t>(i)) {
      problems += (problems.empty() ? "" : "; ") + ("\"" + w + "\" is listed twice");
    }
  }
  if (problems.empty()) return problems;
  std::string valid;
  for (const std::string& c : columns) valid += (valid.empty() ? "" : ", ") + c;
  return problems + " (valid: " + valid + ")";
}

namespace {

// The CSV text, row by row, to `emit` (a few kilobytes at a time): written straight to a file, the table is
// never held twice (a 900 s ship recorded every tick is 150 MB of text).
template <class Emit>
void csv_rows(const std::vector<std::string>& columns, const std::vector<double>& data, std::int64_t rows,
              std::int64_t width, Emit&& emit) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) out += (c ? "," : "") + columns[c];
  out += '\n';
  char buf[32];
  for (std::int64_t r = 0; r < rows; ++r) {
    for (std::int64_t c = 0; c < width; ++c) {
      // %.17g: the CSV round-trips every double, so two runs compare bit for bit.
      std::snprintf(buf, sizeof buf, "%s%.17g", c ? "," : "", data[static_cast<std::size_t>(r * width + c)]);
      out += buf;
    }
    out += '\n';
    if (out.size() > 65536) {
      emit(out);
      out.clear();
    }
  }
  emit(out);
}

}  // namespace

std::string Recorder::csv() const {
  flush();
  std::string all;
  csv_rows(columns_, data_, rows_, width_, [&](const std::string& part) { all += part; });
  return all;
}

bool Recorder::write_csv(const std::string& path, std::string& error) const {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    error = "cannot write " + path;
    return false;
  }
  flush();
  bool ok = true;
  csv_rows(columns_, data_, rows_, width_, [&](const std::string& part) {
    ok = ok && std::fwrite(part.data(), 1, part.size(), f) == part.size();
  });
  ok = ok && std::fflush(f) == 0 && !std::ferror(f);
  if (std::fclose(f) != 0 || !ok) {
    error = "error writing " + path;
    return false;
  }
  return true;
}

}  // namespace gyrostab::tools
