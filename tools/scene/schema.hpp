// One scene schema per device: a table of fields over the device's scene struct — section, key, unit, range,
// description, and accessors into the struct — and a list of rules that relate several keys. The struct's
// member initializers are the defaults, written once: a key absent from the file leaves its member as the
// struct has it. The reader (schema::read) walks the table through SceneReader, so every problem is reported
// with file:line, section and key, all at once, and keys the table does not name are refused; docs/scenes.md
// is generated from the same tables (schema::document, `gyrostab scene-keys`).
//
//   using F = schema::Fields<ShipScene>;
//   constexpr schema::Field<ShipScene> kFields[] = {
//       F::number("ship", "A", "kg m²", Range::positive(), "roll inertia", GS_NUMBER(ship.A)).req(),
//       F::number("gyro", "beta_stop_deg", "deg", Range::open_closed(0, 89), "end stops", GS_NUMBER(ship.beta_stop))
//           .degrees(),
//       F::choice("sea", "kind", kSeaKinds, "wave model", GS_CHOICE(sea.kind)),
//       F::number("sea", "E0", "N m", Range::non_negative(), "amplitude", GS_NUMBER(sea.wave.E0))
//           .req().when(regular_sea, "regular"),
//   };
//   schema::read(r, kFields, scene);
// Docs: docs/adding-a-device.md.
#pragma once

#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "tools/scene/scene_doc.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools::schema {

enum class Kind : std::uint8_t { kNumber, kInteger, kFlag, kChoice, kText, kStrings };

inline constexpr double kDegree = std::numbers::pi / 180.0;

template <class S>
struct Field {
  std::string_view section, key;
  Kind kind{Kind::kNumber};
  std::string_view unit;  // as written in the file ("deg" for a member held in rad)
  std::string_view what;
  bool required{false};
  Range range{};                       // kNumber, in the file's unit
  std::int64_t lo{0}, hi{0};           // kInteger
  double scale{1.0};                   // member = scale × value in the file
  std::span<const std::string_view> options{};  // kChoice: the member holds the option's index
  void (*set_number)(S&, double){};
  double (*get_number)(const S&){};
  void (*set_integer)(S&, std::int64_t){};
  std::int64_t (*get_integer)(const S&){};
  void (*set_flag)(S&, bool){};
  bool (*get_flag)(const S&){};
  void (*set_choice)(S&, int){};
  int (*get_choice)(const S&){};
  void (*set_text)(S&, const std::string&){};
  std::string_view (*get_text)(const S&){};
  void (*set_strings)(S&, std::vector<std::string>&&){};
  // The key exists only when `applies` holds for what was read before it (docs: "<applies_doc>: ...");
  // otherwise the key is unknown and a file that sets it is refused.
  bool (*applies)(const S&){};
  std::string_view applies_doc;
  // A default that follows other keys (the struct's member initializer otherwise).
  double (*default_of)(const S&){};
  std::string_view default_doc;
  // A range that follows other keys.
  Range (*range_of)(const S&){};
  std::string_view range_doc;
  std::string_view note;  // docs only: appended to the meaning

  constexpr Field req() const {
    Field f = *this;
    f.required = true;
    return f;
  }
  constexpr Field when(bool (*p)(const S&), std::string_view doc) const {
    Field f = *this;
    f.applies = p;
    f.applies_doc = doc;
    return f;
  }
  constexpr Field defaults_to(double (*d)(const S&), std::string_view doc) const {
    Field f = *this;
    f.default_of = d;
    f.default_doc = doc;
    return f;
  }
  constexpr Field within(Range (*r)(const S&), std::string_view doc) const {
    Field f = *this;
    f.range_of = r;
    f.range_doc = doc;
    return f;
  }
  constexpr Field degrees() const {
    Field f = *this;
    f.scale = kDegree;
    return f;
  }
  constexpr Field scaled(double s) const {
    Field f = *this;
    f.scale = s;
    return f;
  }
  constexpr Field with_note(std::string_view n) const {
    Field f = *this;
    f.note = n;
    return f;
  }
};

// A relation between keys, checked once every key read is valid. `check` returns "" or the problem.
template <class S>
struct Rule {
  std::string_view section, key;  // where the message points
  std::string_view doc;           // the rule in words, for the docs
  std::string (*check)(const S&);
};

template <class S>
struct Fields {
  using F = Field<S>;
  static constexpr F number(std::string_view section, std::string_view key, std::string_view unit, Range range,
                            std::string_view what, void (*set)(S&, double), double (*get)(const S&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kNumber, f.unit = unit, f.what = what, f.range = range;
    f.set_number = set, f.get_number = get;
    return f;
  }
  static constexpr F integer(std::string_view section, std::string_view key, std::string_view unit, std::int64_t lo,
                             std::int64_t hi, std::string_view what, void (*set)(S&, std::int64_t),
                             std::int64_t (*get)(const S&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kInteger, f.unit = unit, f.what = what, f.lo = lo, f.hi = hi;
    f.set_integer = set, f.get_integer = get;
    return f;
  }
  static constexpr F flag(std::string_view section, std::string_view key, std::string_view what,
                          void (*set)(S&, bool), bool (*get)(const S&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kFlag, f.what = what;
    f.set_flag = set, f.get_flag = get;
    return f;
  }
  static constexpr F choice(std::string_view section, std::string_view key, std::span<const std::string_view> options,
                            std::string_view what, void (*set)(S&, int), int (*get)(const S&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kChoice, f.what = what, f.options = options;
    f.set_choice = set, f.get_choice = get;
    return f;
  }
  static constexpr F text(std::string_view section, std::string_view key, std::string_view what,
                          void (*set)(S&, const std::string&), std::string_view (*get)(const S&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kText, f.what = what;
    f.set_text = set, f.get_text = get;
    return f;
  }
  static constexpr F strings(std::string_view section, std::string_view key, std::string_view what,
                             void (*set)(S&, std::vector<std::string>&&)) {
    F f{};
    f.section = section, f.key = key, f.kind = Kind::kStrings, f.what = what;
    f.set_strings = set;
    return f;
  }
};

// Accessor pairs for Fields<S>'s builders (a member path relative to the scene struct, e.g. ship.A).
#define GS_NUMBER(m) [](auto& s_, double v_) { s_.m = v_; }, [](const auto& s_) -> double { return s_.m; }
#define GS_INTEGER(m)                                                                 \
  [](auto& s_, std::int64_t v_) { s_.m = static_cast<std::remove_cvref_t<decltype(s_.m)>>(v_); }, \
      [](const auto& s_) -> std::int64_t { return static_cast<std::int64_t>(s_.m); }
#define GS_FLAG(m) [](auto& s_, bool v_) { s_.m = v_; }, [](const auto& s_) -> bool { return s_.m; }
#define GS_CHOICE(m)                                                                 \
  [](auto& s_, int v_) { s_.m = static_cast<std::remove_cvref_t<decltype(s_.m)>>(v_); }, \
      [](const auto& s_) -> int { return static_cast<int>(s_.m); }
#define GS_TEXT(m) \
  [](auto& s_, const std::string& v_) { s_.m = v_; }, [](const auto& s_) -> std::string_view { return s_.m; }
#define GS_STRINGS(m) [](auto& s_, std::vector<std::string>&& v_) { s_.m = std::move(v_); }

// The description in messages: "what [unit]".
template <class S>
std::string describe(const Field<S>& f) {
  std::string w(f.what);
  if (!f.unit.empty()) w += " [" + std::string(f.unit) + "]";
  return w;
}

// Reads every field that applies into `s`; the members of absent keys keep their defaults (or take
// default_of). Marks every key it asks for as known; the caller's r.finish() refuses the rest.
template <class S>
void read(SceneReader& r, std::span<const Field<S>> fields, S& s) {
  for (const Field<S>& f : fields) {
    if (f.applies != nullptr && !f.applies(s)) continue;
    const std::string what = describe(f);
    const bool present = r.has(f.section, f.key);
    switch (f.kind) {
      case Kind::kNumber: {
        const Range range = f.range_of != nullptr ? f.range_of(s) : f.range;
        if (f.required) {
          f.set_number(s, f.scale * r.required(f.section, f.key, range, what));
        } else if (present) {
          constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();
          const double v = r.number(f.section, f.key, kAbsent, range, what);
          if (v == v) f.set_number(s, f.scale * v);  // NaN: refused (the problem is recorded)
        } else {
          r.number(f.section, f.key, 0.0, range, what);  // marks the key known
          if (f.default_of != nullptr) f.set_number(s, f.default_of(s));
        }
        break;
      }
      case Kind::kInteger: {
        const std::int64_t keep = f.get_integer(s);
        f.set_integer(s, r.integer(f.section, f.key, keep, f.lo, f.hi, what));
        break;
      }
      case Kind::kFlag: {
        const bool keep = f.get_flag(s);
        f.set_flag(s, r.flag(f.section, f.key, keep, what));
        break;
      }
      case Kind::kChoice: {
        const int keep = f.get_choice(s);
        const std::string_view fallback = f.options[static_cast<std::size_t>(keep)];
        const std::string v = r.choice_of(f.section, f.key, fallback, f.options, what);
        for (std::size_t i = 0; i < f.options.size(); ++i) {
          if (f.options[i] == v) f.set_choice(s, static_cast<int>(i));
        }
        break;
      }
      case Kind::kText: {
        const std::string keep(f.get_text(s));
        f.set_text(s, r.text(f.section, f.key, keep, what));
        break;
      }
      case Kind::kStrings:
        f.set_strings(s, r.strings(f.section, f.key, what));
        break;
    }
  }
}

// Checks every rule (only when every key read so far was valid: a refused key reads as its default or NaN
// and would trip the relations too).
template <class S>
void check(SceneReader& r, std::span<const Rule<S>> rules, const S& s) {
  if (!r.ok()) return;
  for (const Rule<S>& rule : rules) {
    const std::string why = rule.check(s);
    if (!why.empty()) r.fail(rule.section, rule.key, why);
  }
}

// The tables are arrays: these forward them as spans.
template <class S, std::size_t N>
void read(SceneReader& r, const Field<S> (&fields)[N], S& s) {
  read(r, std::span<const Field<S>>(fields, N), s);
}
template <class S, std::size_t N>
void check(SceneReader& r, const Rule<S> (&rules)[N], const S& s) {
  check(r, std::span<const Rule<S>>(rules, N), s);
}

// Docs formatting (tools/scene/scene_doc.cpp).
std::string format_number(double v);
std::string format_range(const Range& r);
std::string format_integer_range(std::int64_t lo, std::int64_t hi);

template <class S>
SceneDocTable document(std::span<const Field<S>> fields, std::string title = "", std::string note = "") {
  SceneDocTable t{std::move(title), std::move(note), {}};
  const auto d = std::make_unique<S>();
  for (const Field<S>& f : fields) {
    SceneDocRow row;
    row.key = "`[" + std::string(f.section) + "] " + std::string(f.key) + "`";
    row.meaning = f.applies_doc.empty() ? std::string(f.what) : std::string(f.applies_doc) + ": " + std::string(f.what);
    if (!f.note.empty()) row.meaning += "; " + std::string(f.note);
    row.unit = f.unit.empty() ? "–" : std::string(f.unit);
    switch (f.kind) {
      case Kind::kNumber:
        row.fallback = f.required ? "required"
                       : f.default_of != nullptr ? std::string(f.default_doc)
                                                 : format_number(f.get_number(*d) / f.scale);
        row.range = f.range_of != nullptr ? std::string(f.range_doc) : format_range(f.range);
        break;
      case Kind::kInteger:
        row.fallback = std::to_string(f.get_integer(*d));
        row.range = format_integer_range(f.lo, f.hi);
        break;
      case Kind::kFlag:
        row.fallback = f.get_flag(*d) ? "true" : "false";
        row.range = "true, false";
        break;
      case Kind::kChoice: {
        row.fallback = "`" + std::string(f.options[static_cast<std::size_t>(f.get_choice(*d))]) + "`";
        std::string r;
        for (std::string_view o : f.options) r += (r.empty() ? "`" : ", `") + std::string(o) + "`";
        row.range = r;
        break;
      }
      case Kind::kText:
        row.fallback = f.get_text(*d).empty() ? "–" : "`" + std::string(f.get_text(*d)) + "`";
        row.range = "text";
        break;
      case Kind::kStrings:
        row.fallback = "–";
        row.range = "array of strings";
        break;
    }
    if (!f.range_doc.empty() && f.kind != Kind::kNumber) row.range = f.range_doc;
    t.rows.push_back(std::move(row));
  }
  return t;
}

template <class S>
std::vector<std::string> document(std::span<const Rule<S>> rules) {
  std::vector<std::string> out;
  for (const Rule<S>& r : rules) out.emplace_back(r.doc);
  return out;
}

template <class S, std::size_t N>
SceneDocTable document(const Field<S> (&fields)[N], std::string title = "", std::string note = "") {
  return document(std::span<const Field<S>>(fields, N), std::move(title), std::move(note));
}
template <class S, std::size_t N>
std::vector<std::string> document(const Rule<S> (&rules)[N]) {
  return document(std::span<const Rule<S>>(rules, N));
}

}  // namespace gyrostab::tools::schema
