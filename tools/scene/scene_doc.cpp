#include "tools/scene/scene_doc.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "tools/scene/schema.hpp"

namespace gyrostab::tools {

std::string markdown(const SceneDocTable& t) {
  std::string s;
  if (!t.title.empty()) s += "### " + t.title + "\n\n";
  if (!t.note.empty()) s += t.note + "\n\n";
  s += "| key | meaning | unit | default | range |\n|---|---|---|---|---|\n";
  for (const SceneDocRow& r : t.rows) {
    s += "| " + r.key + " | " + r.meaning + " | " + r.unit + " | " + r.fallback + " | " + r.range + " |\n";
  }
  return s;
}

std::string markdown_rules(const std::vector<std::string>& rules) {
  if (rules.empty()) return "";
  std::string s = "Checks that relate several keys (the scene is refused when one fails):\n";
  for (const std::string& r : rules) s += "- " + r + "\n";
  return s;
}

namespace schema {

// Short numbers for the docs: 0.25, 1000, 1e6, 1e-4, −0.1 (a typographic minus).
std::string format_number(double v) {
  char buf[64];
  const double m = std::fabs(v);
  const bool exponent = m != 0.0 && (m >= 1e5 || m < 1e-3);
  std::snprintf(buf, sizeof buf, exponent ? "%.6e" : "%.6g", v);
  std::string s(buf);
  if (exponent) {
    const std::size_t e = s.find('e');
    std::string mant = s.substr(0, e), exp = s.substr(e + 1);
    if (mant.find('.') != std::string::npos) {
      while (mant.back() == '0') mant.pop_back();
      if (mant.back() == '.') mant.pop_back();
    }
    std::string sign;
    if (exp[0] == '+' || exp[0] == '-') {
      if (exp[0] == '-') sign = "-";
      exp = exp.substr(1);
    }
    while (exp.size() > 1 && exp[0] == '0') exp = exp.substr(1);
    s = mant + "e" + sign + exp;
  }
  if (!s.empty() && s[0] == '-') s = "−" + s.substr(1);
  return s;
}

std::string format_range(const Range& r) {
  const bool has_lo = r.lo > -1e307, has_hi = r.hi < 1e307;
  if (has_lo && has_hi) {
    if (r.lo_open && !r.hi_open) return "(" + format_number(r.lo) + ", " + format_number(r.hi) + "]";
    if (!r.lo_open && r.hi_open) return "[" + format_number(r.lo) + ", " + format_number(r.hi) + ")";
    if (r.lo_open && r.hi_open) return "(" + format_number(r.lo) + ", " + format_number(r.hi) + ")";
    return format_number(r.lo) + " … " + format_number(r.hi);
  }
  if (has_lo) return (r.lo_open ? "> " : "≥ ") + format_number(r.lo);
  if (has_hi) return (r.hi_open ? "< " : "≤ ") + format_number(r.hi);
  return "finite";
}

namespace {
std::string power_of_two(std::int64_t v) {
  if (v == INT64_MAX) return "2⁶³ − 1";
  if (v >= 65536 && (v & (v - 1)) == 0) {
    static const char* const kSup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    int n = 0;
    while ((std::int64_t{1} << n) < v) ++n;
    std::string s = "2";
    if (n >= 10) s += kSup[n / 10];
    s += kSup[n % 10];
    return s;
  }
  return std::to_string(v);
}
}  // namespace

std::string format_integer_range(std::int64_t lo, std::int64_t hi) {
  return "integer " + power_of_two(lo) + " … " + power_of_two(hi);
}

}  // namespace schema
}  // namespace gyrostab::tools
