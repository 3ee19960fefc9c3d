// The verdict of a start-up parameter check (a control law's gains, a controller's Config): accepted, or
// refused with a static reason and the numbers that make the reason actionable (the offending value and
// the computed bounds it must lie within). No text formatting on the target: the host prints the numbers.
// Used by every law in firmware/control/ and every controller in firmware/app/.
// Docs: docs/models/README.md#firmware
#pragma once

namespace gyrostab::firmware {

struct ConfigCheck {
  bool ok{true};           // accepted
  const char* reason{""};  // static text: which condition failed (with its book equation), or "" when ok
  double value{0.0};       // the offending value, when a bound was violated [unit of the parameter]
  double lower{0.0};       // computed lower bound for it (0 when the check has none) [same unit]
  double upper{0.0};       // computed upper bound for it (0 when the check has none) [same unit]

  static constexpr ConfigCheck accepted() { return {}; }
  static constexpr ConfigCheck refused(const char* why, double value = 0.0, double lower = 0.0,
                                       double upper = 0.0) {
    return {false, why, value, lower, upper};
  }
};

}  // namespace gyrostab::firmware
