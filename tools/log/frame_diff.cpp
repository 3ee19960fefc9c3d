#include "tools/log/frame_diff.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>

namespace gyrostab::tools::buslog {

namespace {

class Diff {
 public:
  explicit Diff(const char* other) : other_(other) {}

  template <class T>
  void field(const char* name, const T& a, const T& b) {
    if (std::memcmp(&a, &b, sizeof(T)) == 0) return;
    char line[256];
    if constexpr (std::is_same_v<T, double>) {
      std::snprintf(line, sizeof line, "%s: recorded %.17g, %s %.17g", name, a, other_, b);
    } else if constexpr (std::is_signed_v<T>) {
      std::snprintf(line, sizeof line, "%s: recorded %" PRId64 ", %s %" PRId64, name, static_cast<std::int64_t>(a),
                    other_, static_cast<std::int64_t>(b));
    } else {
      std::snprintf(line, sizeof line, "%s: recorded %" PRIu64 " (0x%" PRIx64 "), %s %" PRIu64 " (0x%" PRIx64 ")", name,
                    static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(a), other_,
                    static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(b));
    }
    if (!text_.empty()) text_ += "; ";
    text_ += line;
  }
  const std::string& text() const { return text_; }

 private:
  const char* other_;
  std::string text_;
};

}  // namespace

// The signals by their names in the device's table: "name" for a scalar, "name[i]" for an array's element.
void signals(Diff& d, std::span<const msg::SignalSpec> specs, const double* r, const double* p) {
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const msg::SignalSpec& s = specs[i];
    std::string n(s.name);
    if (s.count > 1) n += "[" + std::to_string(s.element) + "]";
    d.field(n.c_str(), r[i], p[i]);
  }
}

std::string frame_differences(const msg::AnyActuatorFrame& r, const msg::AnyActuatorFrame& p,
                              const msg::DeviceSignals& device) {
  if (std::memcmp(&r, &p, sizeof r) == 0) return {};
  Diff d("replayed");
  d.field("tick", r.tick, p.tick);
  d.field("time_ns", r.time_ns, p.time_ns);
  d.field("sensor_tick", r.sensor_tick, p.sensor_tick);
  d.field("sequence", r.sequence, p.sequence);
  d.field("status", r.status, p.status);
  signals(d, device.commands, r.signal, p.signal);
  return d.text().empty() ? std::string("bytes differ outside the named fields") : d.text();
}

std::string frame_differences(const msg::AnySensorFrame& r, const msg::AnySensorFrame& p,
                              const msg::DeviceSignals& device) {
  if (std::memcmp(&r, &p, sizeof r) == 0) return {};
  Diff d("re-simulated");
  d.field("tick", r.tick, p.tick);
  d.field("time_ns", r.time_ns, p.time_ns);
  d.field("sample_time_ns", r.sample_time_ns, p.sample_time_ns);
  d.field("sequence", r.sequence, p.sequence);
  d.field("status", r.status, p.status);
  signals(d, device.sensors, r.signal, p.signal);
  return d.text().empty() ? std::string("bytes differ outside the named fields") : d.text();
}

}  // namespace gyrostab::tools::buslog
