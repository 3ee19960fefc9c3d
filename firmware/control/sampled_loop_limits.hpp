// Upper limits a sampled loop puts on rate (damping) and angle (stiffness) feedback on a gimbal axis of
// inertia B, run every T seconds with a zero-order hold and up to two ticks of latency (the command of
// tick k is applied from tick k + 1, docs/architecture.md (the loop), plus one tick of margin).
//
// Rate feedback M = −D β' alone: B Δβ'/T = −D β'(delayed) gives β'_{k+1} = β'_k − a β'_{k−n} with
// a = D T / B. One tick of latency (n = 1): z² − z + a, stable iff a < 1; two ticks: z³ − z² + a, stable
// iff a < (√5 − 1)/2 ≈ 0.618 (Jury; checked numerically). We require a ≤ 0.5:  D ≤ 0.5 B / T.
// Stiffness K (M = −K β): ω T ≤ 0.5 with ω = sqrt(K/B), i.e. at least 12 samples per period of the mode the
// stiffness creates:  K ≤ 0.25 B / T².
// These are necessary conditions for the sampled law to behave like the continuous one the book analyses
// (the gyroscopic coupling and the plant's own damping only move the limits a little for ω_N T ≪ 1); they
// guard against a gain typed with the wrong unit or a period chosen far too long. O(1).
// Docs: docs/models/README.md#firmware
#pragma once

namespace gyrostab::firmware {

inline constexpr double kMaxDampingTimesPeriodOverInertia = 0.5;  // D T / B ≤ this [-]
inline constexpr double kMaxNaturalFrequencyTimesPeriod = 0.5;    // sqrt(K/B) T ≤ this [-]

// Largest rate-feedback gain D [N m s/rad] for inertia B [kg m²] at period T [s].
constexpr double max_sampled_damping(double B, double T) {
  return kMaxDampingTimesPeriodOverInertia * B / T;
}
// Largest angle-feedback stiffness K [N m/rad] for inertia B [kg m²] at period T [s].
constexpr double max_sampled_stiffness(double B, double T) {
  return kMaxNaturalFrequencyTimesPeriod * kMaxNaturalFrequencyTimesPeriod * B / (T * T);
}

}  // namespace gyrostab::firmware
