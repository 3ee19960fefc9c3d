#include "tools/sweep/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace gyrostab::tools::sweep {
namespace {

std::string clock_text(double s) {
  if (!(s >= 0.0) || s > 360000.0) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  char buf[32];
  if (t >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%02ld:%02ld", t / 60, t % 60);
  }
  return buf;
}

}  // namespace

ProgressBar::ProgressBar(std::int64_t total, bool quiet)
    : total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

void ProgressBar::draw(std::int64_t done, std::int64_t failed) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double left = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total_ - done) : -1.0;
  const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\rsweep [%s] %lld/%lld tasks, %lld failed, %s elapsed, %s left  ", bar.c_str(),
                 static_cast<long long>(done), static_cast<long long>(total_), static_cast<long long>(failed),
                 clock_text(elapsed).c_str(), clock_text(left).c_str());
  } else {
    std::fprintf(stderr, "sweep: %lld/%lld tasks (%.0f %%), %lld failed, %s elapsed, %s left\n",
                 static_cast<long long>(done), static_cast<long long>(total_), 100.0 * fraction,
                 static_cast<long long>(failed), clock_text(elapsed).c_str(), clock_text(left).c_str());
  }
  std::fflush(stderr);
}

void ProgressBar::update(std::int64_t done, std::int64_t failed) {
  if (quiet_ || total_ <= 0) return;
  if (tty_) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw_ < std::chrono::milliseconds(250)) return;
    last_draw_ = now;
    draw(done, failed);
    return;
  }
  const int tenth = static_cast<int>(10 * done / total_);
  if (tenth > last_tenth_) {
    last_tenth_ = tenth;
    draw(done, failed);
  }
}

void ProgressBar::finish(std::int64_t done, std::int64_t failed) {
  if (quiet_ || total_ <= 0) return;
  if (tty_) {
    draw(done, failed);
    std::fputc('\n', stderr);
  } else if (static_cast<int>(10 * done / total_) > last_tenth_) {
    draw(done, failed);
  }
}

}  // namespace gyrostab::tools::sweep
