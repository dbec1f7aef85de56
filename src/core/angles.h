#pragma once

#include <cmath>
#include <numbers>

namespace semchain {

inline constexpr double kPi = std::numbers::pi;

// Wraps an angle into (-pi, pi].
inline double NormalizeAngle(double angle) {
  // Most angles are already within one turn: fmod(a, 2π) of an a in (0, 2π) is a itself, so the
  // result is the same without the (slow) fmod.
  const double shifted = angle + kPi;
  if (shifted > 0.0 && shifted < 2.0 * kPi) return shifted - kPi;
  double a = std::fmod(shifted, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

// The signed smallest rotation taking 'from' to 'to', in (-pi, pi].
inline double AngleDifference(double to, double from) { return NormalizeAngle(to - from); }

inline constexpr double DegToRad(double degrees) { return degrees * kPi / 180.0; }
inline constexpr double RadToDeg(double radians) { return radians * 180.0 / kPi; }

}  // namespace semchain
