#include "tools/devices/base_motion/base_motion_schema.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "tools/scene/motion_file.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

// The keys as written; converted into the generators after the table (periods to frequencies, the record
// loaded).
struct BaseMotionKeys {
  motion::BaseMotionKind kind{motion::BaseMotionKind::kHarmonicRoll};
  double roll_amplitude{0.0}, roll_period_s{10.0}, roll_phase{0.0};
  double pitch_amplitude{0.0}, pitch_period_s{7.0}, pitch_phase{0.0}, pitch_offset{0.0};
  double yaw_amplitude{0.0}, yaw_period_s{12.0}, yaw_phase{0.0};
  double yaw_rate{0.0};
  double lever_x_m{0.0}, lever_y_m{0.0}, lever_z_m{0.0};
  double heave_amplitude_m{0.0}, heave_frequency_hz{1.0};
  double sway_amplitude_m{0.0}, sway_frequency_hz{1.0};
  std::string file;
  double max_gap_s{0.1};
  double quaternion_tolerance{1e-6};
  double g{motion::kStandardGravity};
};

using K = BaseMotionKeys;
using F = schema::Fields<K>;

constexpr std::string_view kKinds[] = {"harmonic_roll", "prescribed", "recorded"};
bool prescribed(const K& k) { return k.kind == motion::BaseMotionKind::kPrescribed; }
bool recorded(const K& k) { return k.kind == motion::BaseMotionKind::kRecorded; }
bool generated(const K& k) { return !recorded(k); }

constexpr schema::Field<K> kFields[] = {
    F::choice("motion", "kind", kKinds,
              "what moves the base: `harmonic_roll` (the device's own generator: power_stabilizer's [base], "
              "coning's [vibration], gimbal_error's [yaw], [pitch], [roll]), `prescribed` (yaw, pitch, roll "
              "each with one harmonic, a yaw rate, a constant pitch, a lever arm: sim/motion/prescribed_base_rotation.hpp) or "
              "`recorded` (a motion file)",
              GS_CHOICE(kind)),
    F::number("motion", "roll_amplitude_deg", "deg", Range::closed(0.0, 45.0), "roll harmonic amplitude",
              GS_NUMBER(roll_amplitude))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "roll_period_s", "s", Range::closed(0.01, 1e4), "roll period", GS_NUMBER(roll_period_s))
        .when(prescribed, "prescribed"),
    F::number("motion", "roll_phase_deg", "deg", Range::closed(-360.0, 360.0), "roll phase", GS_NUMBER(roll_phase))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "pitch_amplitude_deg", "deg", Range::closed(0.0, 30.0), "pitch harmonic amplitude",
              GS_NUMBER(pitch_amplitude))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "pitch_period_s", "s", Range::closed(0.01, 1e4), "pitch period", GS_NUMBER(pitch_period_s))
        .when(prescribed, "prescribed"),
    F::number("motion", "pitch_phase_deg", "deg", Range::closed(-360.0, 360.0), "pitch phase", GS_NUMBER(pitch_phase))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "pitch_deg", "deg", Range::closed(-90.0, 90.0),
              "constant pitch θ0 of the base: its axis 3 stands θ0 from the world's; with `yaw_rate_deg_s` it runs "
              "round a cone of half-angle θ0 (a base on the Earth at latitude 90° − θ0, world axis 3 the Earth's "
              "axis, turning at the sidereal rate: the Goodman–Robinson setting of Magnus (15.35))",
              GS_NUMBER(pitch_offset))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "yaw_amplitude_deg", "deg", Range::closed(0.0, 45.0), "yaw harmonic amplitude",
              GS_NUMBER(yaw_amplitude))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "yaw_period_s", "s", Range::closed(0.01, 1e4), "yaw period", GS_NUMBER(yaw_period_s))
        .when(prescribed, "prescribed"),
    F::number("motion", "yaw_phase_deg", "deg", Range::closed(-360.0, 360.0), "yaw phase", GS_NUMBER(yaw_phase))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "yaw_rate_deg_s", "deg/s", Range::closed(-30.0, 30.0), "constant turn rate (curve running)",
              GS_NUMBER(yaw_rate))
        .degrees()
        .when(prescribed, "prescribed"),
    F::number("motion", "lever_x_m", "m", Range::closed(-100.0, 100.0),
              "suspension point from the centre of rotation, base axis 1", GS_NUMBER(lever_x_m))
        .when(prescribed, "prescribed"),
    F::number("motion", "lever_y_m", "m", Range::closed(-100.0, 100.0), "… base axis 2", GS_NUMBER(lever_y_m))
        .when(prescribed, "prescribed"),
    F::number("motion", "lever_z_m", "m", Range::closed(-100.0, 100.0),
              "… base axis 3 (a gyro h above the roll axis sees h φ'', Magnus 13.3.3)", GS_NUMBER(lever_z_m))
        .when(prescribed, "prescribed"),
    F::number("motion", "heave_amplitude_m", "m", Range::closed(0.0, 1.0),
              "vertical (base axis 3) vibration displacement amplitude s: a = s ν² cos νt (Magnus (11.53))",
              GS_NUMBER(heave_amplitude_m))
        .when(generated, "harmonic_roll or prescribed"),
    F::number("motion", "heave_frequency_hz", "Hz", Range::closed(1e-3, 1e3), "heave vibration frequency",
              GS_NUMBER(heave_frequency_hz))
        .when(generated, "harmonic_roll or prescribed"),
    F::number("motion", "sway_amplitude_m", "m", Range::closed(0.0, 1.0),
              "horizontal (base axis 2) vibration displacement amplitude", GS_NUMBER(sway_amplitude_m))
        .when(generated, "harmonic_roll or prescribed"),
    F::number("motion", "sway_frequency_hz", "Hz", Range::closed(1e-3, 1e3), "sway vibration frequency",
              GS_NUMBER(sway_frequency_hz))
        .when(generated, "harmonic_roll or prescribed"),
    F::text("motion", "file",
            "the motion record (CSV, docs/models/suspension-motion.md#recorded-motion), relative to the scene "
            "file's directory, inside it or the motion_records/ directory beside it",
            GS_TEXT(file))
        .req()
        .when(recorded, "recorded"),
    F::number("motion", "max_gap_s", "s", Range::closed(1e-6, 10.0),
              "the longest interval between two rows the record may have (the interpolation error grows as h³)",
              GS_NUMBER(max_gap_s))
        .when(recorded, "recorded"),
    F::number("motion", "quaternion_tolerance", "", Range::closed(0.0, 0.1),
              "how far the norm ‖q‖ of a row may be from 1 before the record is refused (then q is normalized)",
              GS_NUMBER(quaternion_tolerance))
        .when(recorded, "recorded"),
    F::number("motion", "g_m_s2", "m/s²", Range::closed(1.0, 30.0),
              "g that turns the record's specific force into up_B = f/g (and reads a column in [g])", GS_NUMBER(g))
        .when(recorded, "recorded"),
};

constexpr const char* kNote =
    "A device whose base moves (`power_stabilizer`, `coning`, `gimbal_error`) can have it moved by a generator or by a recorded motion "
    "(sim/motion/scene_base_motion.hpp). `kind = \"recorded\"` reads a CSV of time, attitude, angular rate and "
    "specific force at scene read time; it is refused, with the file's line, when its times do not increase "
    "strictly (or by less than 1 µs), leave a gap over `max_gap_s`, hold a NaN/inf or a value outside its "
    "column's range (|ω| ≤ 100 rad/s, |f| ≤ 1000 m/s², |t| ≤ 1e7 s), lack or repeat a column, carry a non-unit "
    "quaternion, or do not cover [0, duration_s]. `gyrostab motion-record SCENE --out FILE` writes the motion "
    "of a scene's generator in this format. The format, the interpolation and its error bound: "
    "docs/models/suspension-motion.md#recorded-motion.";

motion::PrescribedAngle<1> angle(double amplitude, double period_s, double phase, double rate) {
  motion::PrescribedAngle<1> a;
  a.rate = rate;
  if (amplitude > 0.0) {
    a.harmonics[0] = {amplitude, 2.0 * std::numbers::pi / period_s, phase};
    a.count = 1;
  }
  return a;
}

}  // namespace

void read_base_motion(SceneReader& r, motion::SceneBaseMotion& m, double duration_s) {
  K k;
  schema::read(r, kFields, k);
  m.kind = k.kind;
  if (prescribed(k)) {
    m.prescribed.roll = angle(k.roll_amplitude, k.roll_period_s, k.roll_phase, 0.0);
    m.prescribed.pitch = angle(k.pitch_amplitude, k.pitch_period_s, k.pitch_phase, 0.0);
    m.prescribed.pitch.offset = k.pitch_offset;
    m.prescribed.yaw = angle(k.yaw_amplitude, k.yaw_period_s, k.yaw_phase, k.yaw_rate);
    m.prescribed.lever_arm_B = {k.lever_x_m, k.lever_y_m, k.lever_z_m};
  }
  if (generated(k)) {
    int n = 0;
    if (k.heave_amplitude_m > 0.0)
      m.vibration.harmonics[n++] = {{0.0, 0.0, k.heave_amplitude_m}, 2.0 * std::numbers::pi * k.heave_frequency_hz, 0.0};
    if (k.sway_amplitude_m > 0.0)
      m.vibration.harmonics[n++] = {{0.0, k.sway_amplitude_m, 0.0}, 2.0 * std::numbers::pi * k.sway_frequency_hz, 0.0};
    m.vibration.count = n;
  }
  if (!recorded(k) || !r.ok()) return;
  std::vector<std::string> problems;
  const MotionCsvLimits limits{k.max_gap_s, k.quaternion_tolerance, k.g};
  std::shared_ptr<const motion::MotionRecord> record = load_motion_file(k.file, r.file_root(), limits, problems);
  for (const std::string& p : problems) r.fail("motion", "file", p);
  if (record == nullptr) return;
  const double t0 = record->t.front(), t1 = record->t.back();
  if (t0 > 0.0 || t1 < duration_s) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "the record covers [%.6g, %.6g] s; the scene runs over [0, %.6g] s", t0, t1,
                  duration_s);
    r.fail("motion", "file", std::string(k.file) + ": " + buf);
    return;
  }
  m.recorded = motion::RecordedMotion(std::move(record), k.g);
}

SceneDocTable base_motion_doc() { return schema::document(kFields, "base motion", kNote); }

}  // namespace gyrostab::tools
