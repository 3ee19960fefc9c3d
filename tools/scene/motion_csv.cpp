// A small strict reader rather than a CSV library: the format is numbers only (no quoting, no embedded
// commas), the project's dependencies have none, and a strict grammar is what lets every refusal name its line.
#include "tools/scene/motion_csv.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

namespace gyrostab::tools {
namespace {

constexpr std::size_t kMaxProblems = 20;
constexpr double kDeg = std::numbers::pi / 180.0;

enum Column : int { kT, kQ0, kQ1, kQ2, kQ3, kRoll, kPitch, kYaw, kWx, kWy, kWz, kFx, kFy, kFz, kColumns };

struct ColumnSpec {
  std::string_view name;
  std::array<std::string_view, 3> units;  // accepted units ("" for a dimensionless column)
  std::array<double, 3> scale;            // each unit's factor to SI
  double max_abs;                         // the largest magnitude accepted, in SI (header of motion_csv.hpp)
  std::string_view si_unit;               // for the message
};

// Ranges: a recorded base moves like a vehicle or a test table, not like a number the file happens to hold.
// |ω| ≤ 100 rad/s (5730 °/s, above any IMU's range), |f| ≤ 1000 m/s² (102 g), |t| ≤ 1e7 s (116 days),
// angles ≤ 1e6 rad unwrapped; the quaternion's components are held by its norm check.
constexpr double kMaxTime = 1e7, kMaxAngle = 1e6, kMaxRate = 100.0, kMaxForce = 1000.0;

constexpr std::array<ColumnSpec, kColumns> kSpecs{{
    {"t", {"s"}, {1.0}, kMaxTime, "s"},
    {"q0", {"", "-"}, {1.0, 1.0}, 2.0, ""},
    {"q1", {"", "-"}, {1.0, 1.0}, 2.0, ""},
    {"q2", {"", "-"}, {1.0, 1.0}, 2.0, ""},
    {"q3", {"", "-"}, {1.0, 1.0}, 2.0, ""},
    {"roll", {"deg", "rad"}, {kDeg, 1.0}, kMaxAngle, "rad"},
    {"pitch", {"deg", "rad"}, {kDeg, 1.0}, kMaxAngle, "rad"},
    {"yaw", {"deg", "rad"}, {kDeg, 1.0}, kMaxAngle, "rad"},
    {"wx", {"rad/s", "deg/s"}, {1.0, kDeg}, kMaxRate, "rad/s"},
    {"wy", {"rad/s", "deg/s"}, {1.0, kDeg}, kMaxRate, "rad/s"},
    {"wz", {"rad/s", "deg/s"}, {1.0, kDeg}, kMaxRate, "rad/s"},
    {"fx", {"m/s^2", "m/s²", "g"}, {1.0, 1.0, 0.0}, kMaxForce, "m/s^2"},
    {"fy", {"m/s^2", "m/s²", "g"}, {1.0, 1.0, 0.0}, kMaxForce, "m/s^2"},
    {"fz", {"m/s^2", "m/s²", "g"}, {1.0, 1.0, 0.0}, kMaxForce, "m/s^2"},
}};
// The shortest interval between two rows: the node slopes are differences over it, and a rate step of
// 2 × 100 rad/s over 1 µs is still a finite 2e8 rad/s².
constexpr double kMinInterval = 1e-6;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// At most 40 characters of what the file held, printable ASCII only: a message quotes the file, never dumps it.
std::string quote(std::string_view s) {
  std::string q;
  for (char c : s.substr(0, 40)) q += (c >= 0x20 && c < 0x7f) ? c : '?';
  return "'" + q + (s.size() > 40 ? "...'" : "'");
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

class Problems {
 public:
  Problems(const std::string& name, std::vector<std::string>& out) : name_(name), out_(out) {}
  void at(std::size_t line, const std::string& m) {
    if (++count_ <= kMaxProblems) out_.push_back(name_ + ":" + std::to_string(line) + ": " + m);
  }
  void whole(const std::string& m) {
    if (++count_ <= kMaxProblems) out_.push_back(name_ + ": " + m);
  }
  void close() {
    if (count_ > kMaxProblems) out_.push_back(name_ + ": ... and " + std::to_string(count_ - kMaxProblems) + " more");
  }
  bool any() const { return count_ > 0; }

 private:
  const std::string& name_;
  std::vector<std::string>& out_;
  std::size_t count_{0};
};

struct Header {
  std::array<int, kColumns> index{};  // field index of each column, -1 absent
  std::array<double, kColumns> scale{};
  std::size_t fields{0};
  bool quaternion{false};
};

std::optional<Header> read_header(std::string_view line, std::size_t n, const MotionCsvLimits& lim, Problems& p) {
  Header h;
  h.index.fill(-1);
  const std::vector<std::string_view> cells = split(line);
  h.fields = cells.size();
  bool ok = true;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    std::string_view cell = cells[k], unit;
    if (const std::size_t open = cell.find('['); open != std::string_view::npos) {
      if (cell.back() != ']') {
        p.at(n, "column " + std::to_string(k + 1) + " " + quote(cell) + ": a unit is written `name [unit]`");
        ok = false;
        continue;
      }
      unit = trim(cell.substr(open + 1, cell.size() - open - 2));
      cell = trim(cell.substr(0, open));
    }
    int c = 0;
    while (c < kColumns && kSpecs[c].name != cell) ++c;
    if (c == kColumns) {
      p.at(n, "unknown column " + quote(cell) + " (known: t, q0..q3 or roll/pitch/yaw, wx wy wz, fx fy fz)");
      ok = false;
      continue;
    }
    if (h.index[c] >= 0) {
      p.at(n, "column " + quote(cell) + " appears twice");
      ok = false;
      continue;
    }
    const ColumnSpec& s = kSpecs[c];
    int u = 0;
    while (u < 3 && !(s.units[u] == unit && (u == 0 || !s.units[u].empty()))) ++u;
    if (u == 3) {
      std::string allowed;
      for (std::string_view a : s.units) {
        if (!a.empty()) allowed += (allowed.empty() ? "[" : ", [") + std::string(a) + "]";
      }
      p.at(n, "column " + quote(cell) + (unit.empty() ? " needs a unit: " : " has unit " + quote(unit) + "; allowed: ") +
                  allowed);
      ok = false;
      continue;
    }
    h.index[c] = static_cast<int>(k);
    h.scale[c] = s.units[u] == "g" ? lim.g : s.scale[u];
  }
  const auto has = [&](std::initializer_list<int> cs) {
    int n_has = 0;
    for (int c : cs) n_has += h.index[c] >= 0;
    return n_has;
  };
  if (!ok) return std::nullopt;
  const int nq = has({kQ0, kQ1, kQ2, kQ3}), ne = has({kRoll, kPitch, kYaw});
  if (h.index[kT] < 0) p.at(n, "missing column t [s]"), ok = false;
  if (nq > 0 && ne > 0) p.at(n, "give the attitude once: q0..q3 or roll/pitch/yaw, not both"), ok = false;
  else if (nq != 4 && ne != 3) p.at(n, "missing attitude columns: q0, q1, q2, q3 or roll, pitch, yaw"), ok = false;
  if (has({kWx, kWy, kWz}) != 3) p.at(n, "missing angular rate columns: wx, wy, wz"), ok = false;
  if (has({kFx, kFy, kFz}) != 3) p.at(n, "missing specific force columns: fx, fy, fz"), ok = false;
  h.quaternion = nq == 4;
  if (!ok) return std::nullopt;
  return h;
}

}  // namespace

bool parse_motion_csv(std::string_view text, const std::string& name, const MotionCsvLimits& lim,
                      motion::MotionRecord& out, std::vector<std::string>& problems) {
  Problems p(name, problems);
  out = {};
  std::optional<Header> header;
  std::size_t line_no = 0, prev_line = 0;
  std::array<double, kColumns> v{};
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line = trim(text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos));
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    if (!header) {
      header = read_header(line, line_no, lim, p);
      if (!header) break;  // the rows cannot be read without it
      continue;
    }
    const std::vector<std::string_view> cells = split(line);
    if (cells.size() != header->fields) {
      p.at(line_no, std::to_string(cells.size()) + " fields, the header has " + std::to_string(header->fields));
      continue;
    }
    bool row_ok = true;
    for (int c = 0; c < kColumns; ++c) {
      if (header->index[c] < 0) continue;
      const std::string_view cell = cells[static_cast<std::size_t>(header->index[c])];
      double x = 0.0;
      const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
      if (cell.empty() || ec != std::errc() || end != cell.data() + cell.size()) {
        p.at(line_no, "column " + std::string(kSpecs[c].name) + ": " + quote(cell) + " is not a number");
        row_ok = false;
      } else if (!std::isfinite(x)) {
        p.at(line_no, "column " + std::string(kSpecs[c].name) + ": " + quote(cell) + " is not finite");
        row_ok = false;
      }
      v[c] = x * header->scale[c];
      if (row_ok && !(std::abs(v[c]) <= kSpecs[c].max_abs)) {
        p.at(line_no, "column " + std::string(kSpecs[c].name) + ": " + quote(cell) + " is " + fmt(v[c]) + " " +
                          std::string(kSpecs[c].si_unit) + ", outside ±" + fmt(kSpecs[c].max_abs) + " " +
                          std::string(kSpecs[c].si_unit));
        row_ok = false;
      }
    }
    if (!row_ok) continue;
    if (!out.t.empty()) {
      const double dt = v[kT] - out.t.back();
      if (!(dt > 0.0)) {
        p.at(line_no, "time " + fmt(v[kT]) + " s does not follow line " + std::to_string(prev_line) + "'s " +
                          fmt(out.t.back()) + " s: times must increase strictly");
        continue;
      } else if (dt < kMinInterval) {
        p.at(line_no, "time " + fmt(v[kT]) + " s is " + fmt(dt) + " s after line " + std::to_string(prev_line) +
                          "'s: rows must be at least " + fmt(kMinInterval) + " s apart");
        continue;
      } else if (dt > lim.max_gap_s) {
        p.at(line_no, "a gap of " + fmt(dt) + " s after line " + std::to_string(prev_line) +
                          " exceeds max_gap_s = " + fmt(lim.max_gap_s) + " s");
      }
    }
    dynamics::Quat q;
    if (header->quaternion) {
      q = dynamics::Quat(v[kQ0], v[kQ1], v[kQ2], v[kQ3]);
      const double norm = q.norm();
      if (!(std::abs(norm - 1.0) <= lim.quaternion_tolerance)) {
        p.at(line_no, "quaternion norm " + fmt(norm) + " differs from 1 by more than quaternion_tolerance = " +
                          fmt(lim.quaternion_tolerance));
        continue;
      }
      q.normalize();
    } else {
      q = dynamics::Quat(Eigen::AngleAxisd(v[kYaw], dynamics::Vec3::UnitZ()) *
                         Eigen::AngleAxisd(v[kPitch], dynamics::Vec3::UnitY()) *
                         Eigen::AngleAxisd(v[kRoll], dynamics::Vec3::UnitX()));
    }
    out.t.push_back(v[kT]);
    out.q_WB.push_back(q);
    out.w_B.emplace_back(v[kWx], v[kWy], v[kWz]);
    out.f_B.emplace_back(v[kFx], v[kFy], v[kFz]);
    prev_line = line_no;
  }
  if (!header && !p.any()) p.whole("no header line (and no data)");
  if (header && !p.any() && out.size() < 3) {
    p.whole(std::to_string(out.size()) + " rows: a record needs at least 3 (the slopes are three-point differences)");
  }
  p.close();
  if (p.any()) return false;
  out.finish();
  return true;
}

std::string motion_csv_header() {
  return "t [s], q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]";
}

void write_motion_csv_row(std::FILE* f, double t, const dynamics::Quat& q, const dynamics::Vec3& w,
                          const dynamics::Vec3& a) {
  // %.17g: the reader gets back the very doubles written, so a replay differs from the generator only by the
  // interpolation.
  std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, q.w(), q.x(), q.y(), q.z(),
               w.x(), w.y(), w.z(), a.x(), a.y(), a.z());
}

}  // namespace gyrostab::tools
