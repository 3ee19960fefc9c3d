#include "tools/log/frame_diff.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstring>

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
  template <class T, std::size_t N>
  void array(const char* name, const T (&a)[N], const T (&b)[N]) {
    for (std::size_t i = 0; i < N; ++i) {
      const std::string n = std::string(name) + "[" + std::to_string(i) + "]";
      field(n.c_str(), a[i], b[i]);
    }
  }
  const std::string& text() const { return text_; }

 private:
  const char* other_;
  std::string text_;
};

}  // namespace

std::string frame_differences(const msg::ActuatorFrame& r, const msg::ActuatorFrame& p) {
  if (std::memcmp(&r, &p, sizeof r) == 0) return {};
  Diff d("replayed");
  d.field("tick", r.tick, p.tick);
  d.field("time_ns", r.time_ns, p.time_ns);
  d.field("sensor_tick", r.sensor_tick, p.sensor_tick);
  d.field("sequence", r.sequence, p.sequence);
  d.field("status", r.status, p.status);
  d.array("gimbal_torque_Nm", r.gimbal_torque_Nm, p.gimbal_torque_Nm);
  d.array("motor_voltage_V", r.motor_voltage_V, p.motor_voltage_V);
  d.field("precession_brake", r.precession_brake, p.precession_brake);
  d.array("cluster_rate_command_rad_s", r.cluster_rate_command_rad_s, p.cluster_rate_command_rad_s);
  return d.text().empty() ? std::string("bytes differ outside the named fields") : d.text();
}

std::string frame_differences(const msg::SensorFrame& r, const msg::SensorFrame& p) {
  if (std::memcmp(&r, &p, sizeof r) == 0) return {};
  Diff d("re-simulated");
  d.field("tick", r.tick, p.tick);
  d.field("time_ns", r.time_ns, p.time_ns);
  d.field("sample_time_ns", r.sample_time_ns, p.sample_time_ns);
  d.field("sequence", r.sequence, p.sequence);
  d.field("status", r.status, p.status);
  d.array("carrier_angle_rad", r.carrier_angle_rad, p.carrier_angle_rad);
  d.array("carrier_rate_rad_s", r.carrier_rate_rad_s, p.carrier_rate_rad_s);
  d.array("gimbal_angle_rad", r.gimbal_angle_rad, p.gimbal_angle_rad);
  d.array("gimbal_rate_rad_s", r.gimbal_rate_rad_s, p.gimbal_rate_rad_s);
  d.array("motor_current_A", r.motor_current_A, p.motor_current_A);
  d.field("rotor_speed_rad_s", r.rotor_speed_rad_s, p.rotor_speed_rad_s);
  d.array("encoder_count", r.encoder_count, p.encoder_count);
  d.array("cluster_gimbal_angle_rad", r.cluster_gimbal_angle_rad, p.cluster_gimbal_angle_rad);
  d.array("cluster_gimbal_rate_rad_s", r.cluster_gimbal_rate_rad_s, p.cluster_gimbal_rate_rad_s);
  return d.text().empty() ? std::string("bytes differ outside the named fields") : d.text();
}

}  // namespace gyrostab::tools::buslog
