#pragma once
// Mathematical constants and the speed conversions used across turbodyn (everything inside is SI; rpm exists
// only in input, output and messages).

#include <limits>

namespace turbodyn {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
/// A quiet NaN: the value of a quantity that a run or a study could not determine.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// rad/s to rpm: multiply an angular speed by this to print it in rpm.
inline constexpr double kRadPerSToRpm = 60.0 / (2.0 * kPi);
/// rpm to rad/s.
inline constexpr double kRpmToRadPerS = 2.0 * kPi / 60.0;

}  // namespace turbodyn
