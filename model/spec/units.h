#pragma once
// Physical quantities in model input files.
//
// A quantity is either a plain number, taken as SI, or a string "<number> <unit expression>" such as "15 um",
// "150000 rpm" or "7850 kg/m^3". parse_quantity() turns such a string into the SI value of the dimension the
// caller expects and throws UnitError, quoting the input and naming the expected dimension, when it cannot.
// Everything inside turbodyn is SI (kg, m, s, K, rad); units exist only at this boundary.
//
// Grammar
//   quantity   := number [unit]            the space between them is optional: "15um"; spaces (also U+00A0)
//                                          may surround the whole and the operators: "200 N * s / m"
//   number     := anything std::from_chars reads as a finite double, optionally with a leading '+'
//   unit       := factor { ('*' | '·' | '/') factor }, evaluated left to right: "N*m*s/rad", "kg/m/s"
//                 The first factor may be a literal 1 (or be left out) for reciprocals: "2500 1/s", "2500/s".
//   factor     := name ['^' integer]        "m^2", "s^-1"; '²' and '³' are accepted for ^2 and ^3
//   name       := [prefix] unit name       prefixes only on metric units: G M k m u µ n, and c only in "cm"
//                 (both U+00B5 MICRO SIGN and U+03BC GREEK SMALL LETTER MU are accepted as µ)
//
// Units: m, in/inch, g, s, min, h, N, Pa, bar, J, W, Hz, K, degC (or °C), rad, deg (or °), rev, rpm, P, cP.
//
// Temperature: "K" is kelvin. "degC" is an offset scale (90 degC = 363.15 K), so it is only accepted as the whole
// unit; inside a compound ("degC/s") its meaning would be a difference, which must be written in K.
//
// Angles (rotordynamics convention): the angle is a base dimension of its own, so "rad/s" (angular speed) and
// "1/s" (frequency) differ. A quantity without an angle exponent counts whole cycles: Hz is one cycle per second,
// i.e. it is defined as (2*pi rad)/s, rev = 2*pi rad and rpm = 2*pi/60 rad/s. When the dimensions of the
// input and the expected quantity agree except for the angle exponent, the value is converted by
// (2*pi)^(expected.rad - given.rad):
//   "2500 Hz"    as an angular speed -> 2500*2*pi rad/s      "150000 rpm" as a frequency -> 2500 1/s
//   "10 kHz"     as a frequency      -> 1e4 1/s              "1 rad/s"    as a frequency -> 1/(2*pi) 1/s
//   "1 1/s"      as an angular speed -> 2*pi rad/s
// The rule applies only between rates of time (frequency, angular speed, angular acceleration). Elsewhere a
// missing or extra angle is an error: "1 N*m" given for a rotational stiffness (N*m/rad), or "90 deg" for a
// plain number, is far more likely a slip than a count of turns. Quantities without angles are unaffected.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace turbodyn {

// Exponents of the base dimensions: mass (kg), length (m), time (s), temperature (K), angle (rad).
struct Dimension {
  int kg = 0, m = 0, s = 0, K = 0, rad = 0;

  friend bool operator==(const Dimension&, const Dimension&) = default;

  // The SI unit, readable and itself accepted by parse_quantity: "m", "N/m", "kg*m^2", "rad/s", "Hz",
  // "1" for dimensionless.
  std::string si_unit() const;
};

constexpr Dimension operator*(const Dimension& a, const Dimension& b) {
  return {a.kg + b.kg, a.m + b.m, a.s + b.s, a.K + b.K, a.rad + b.rad};
}

constexpr Dimension operator/(const Dimension& a, const Dimension& b) {
  return {a.kg - b.kg, a.m - b.m, a.s - b.s, a.K - b.K, a.rad - b.rad};
}

// The quantities the model uses.
namespace dim {
inline constexpr Dimension dimensionless{}, length{0, 1}, mass{1}, time{0, 0, 1}, temperature{0, 0, 0, 1},
    angle{0, 0, 0, 0, 1};

inline constexpr Dimension area = length * length;
inline constexpr Dimension velocity = length / time;
inline constexpr Dimension acceleration = velocity / time;
inline constexpr Dimension frequency = dimensionless / time;                  // 1/s, cycles per second
inline constexpr Dimension angular_speed = angle / time;                      // rad/s
inline constexpr Dimension angular_acceleration = angular_speed / time;       // rad/s^2
inline constexpr Dimension force = mass * acceleration;                       // N
inline constexpr Dimension pressure = force / area;                           // Pa
inline constexpr Dimension stiffness = force / length;                        // N/m
inline constexpr Dimension damping = force / velocity;                        // N*s/m
inline constexpr Dimension density = mass / (area * length);                  // kg/m^3
inline constexpr Dimension inertia = mass * area;                             // kg*m^2
inline constexpr Dimension unbalance = mass * length;                         // kg*m
inline constexpr Dimension viscosity = pressure * time;                       // Pa*s
inline constexpr Dimension moment = force * length;                           // N*m
inline constexpr Dimension rotational_stiffness = moment / angle;             // N*m/rad
inline constexpr Dimension rotational_damping = rotational_stiffness * time;  // N*m*s/rad
inline constexpr Dimension power = force * velocity;                         // W
inline constexpr Dimension thermal_conductance = power / temperature;         // W/K
inline constexpr Dimension thermal_conductivity = thermal_conductance / length;  // W/(m*K)
inline constexpr Dimension specific_heat = power * time / (mass * temperature);  // J/(kg*K)
}  // namespace dim

// Human-readable name with article and SI unit: "a length (m)", "a stiffness (N/m)", "an angular speed (rad/s)";
// dimensions without a name give "a quantity in <si_unit>".
std::string describe(const Dimension& d);

class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses "<number> <unit expression>" (see the grammar above) and returns the value in SI units of `expected`.
// A bare number ("1e-3") is already SI. Throws UnitError on an empty or malformed string, a missing or
// non-finite number, an unknown unit (with suggestions), a dimension other than `expected`, degC inside a
// compound unit, or a non-integer exponent.
double parse_quantity(std::string_view text, const Dimension& expected);

// The unit part of a quantity as parse_quantity reads it: the trimmed text after the leading number ("150000 rpm"
// -> "rpm", "3.5" -> ""), or nullopt if the text does not start with a finite number.
std::optional<std::string> quantity_unit(std::string_view text);

}  // namespace turbodyn
