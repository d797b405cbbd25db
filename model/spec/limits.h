// What input the program accepts at all: plausible magnitudes of physical quantities and the resource limits
// (element counts, grid sizes, speeds), checked where input is read so that nonsense ends in a located error
// instead of an overflow, an endless loop in an eigen-solver or an allocation of gigabytes. docs/model-format.md
// ("Limits") lists the same numbers.
//
// The magnitude windows are wide on purpose: many orders of magnitude beyond any turbocharger, so that they only
// refuse values that are unit slips or typos (1e306 N/m, 7.8e-297 kg/m^3) and whose squares and products the
// model forms (inertias ~ d^4, masses ~ rho d^2 L) stay far from overflow and underflow.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "model/spec/units.h"

namespace turbodyn::limits {

/// Smallest and largest magnitude |v| of a nonzero value, in SI units. Zero is judged by the reader's own rule
/// (positive, non-negative); the window applies to every nonzero value.
struct Magnitude {
  double smallest, largest;
};

inline Magnitude plausible_magnitude(const Dimension& d) {
  if (d == dim::length) return {1e-10, 1e4};               // 0.1 nm .. 10 km
  if (d == dim::mass) return {1e-9, 1e6};                  // 1 ug .. 1000 t
  if (d == dim::inertia) return {1e-18, 1e6};              // kg m^2
  if (d == dim::density) return {1e-3, 1e5};               // kg/m^3
  if (d == dim::pressure) return {1e-3, 1e14};             // Pa (moduli, supply pressures)
  if (d == dim::stiffness) return {1e-6, 1e13};            // N/m
  if (d == dim::damping) return {1e-9, 1e10};              // N s/m
  if (d == dim::angular_speed) return {1e-9, 1e6};         // rad/s (1e6 rad/s ~ 9.5 million rpm)
  if (d == dim::frequency) return {1e-9, 1e9};             // 1/s
  if (d == dim::time) return {1e-12, 1e7};                 // s (a run of 1e7 s is 115 days)
  if (d == dim::temperature) return {1e-6, 1e4};           // K (also temperature differences)
  if (d == dim::viscosity) return {1e-7, 1e5};             // Pa s
  if (d == dim::unbalance) return {1e-15, 1e3};            // kg m
  if (d == dim::angle) return {1e-12, 1e6};                // rad
  if (d == dim::velocity) return {1e-12, 1e6};             // m/s
  if (d == dim::acceleration) return {1e-9, 1e7};          // m/s^2
  if (d == dim::force) return {1e-9, 1e10};                // N
  if (d == dim::dimensionless) return {1e-20, 1e12};       // ratios, tolerances, orders
  if (d == dim::thermal_conductance) return {1e-9, 1e6};   // W/K
  if (d == dim::thermal_conductivity) return {1e-4, 1e4};  // W/(m K): gases to diamond
  if (d == dim::specific_heat) return {1.0, 1e5};          // J/(kg K)
  return {1e-30, 1e30};
}

/// "" if v is zero or its magnitude lies in the window of d; else the reason, in the user's terms.
inline std::string implausible(double v, const Dimension& d) {
  std::ostringstream os;
  if (!std::isfinite(v)) {
    os << "value is not finite";
    return os.str();
  }
  const Magnitude m = plausible_magnitude(d);
  const double a = std::abs(v);
  if (a == 0.0 || (a >= m.smallest && a <= m.largest)) return "";
  os << v << " " << d.si_unit() << " is " << (a < m.smallest ? "implausibly small" : "implausibly large") << " for "
     << describe(d) << ": accepted magnitudes are " << m.smallest << " to " << m.largest << " " << d.si_unit()
     << " (or 0 where allowed); a unit mistake?";
  return os.str();
}

// Resource limits: each bounds the memory or time a model can ask for, and is refused up front with the estimate.
inline constexpr long kMaxShaftElements = 1000;   ///< beam elements of the shaft mesh (dense matrices of 4 DOF/node)
inline constexpr long kMaxFilmCirc = 2048;        ///< film grid nodes around (n_circ)
inline constexpr long kMaxFilmAxial = 512;        ///< film grid nodes across (n_axial)
inline constexpr long kMaxFilmNodes = 65536;      ///< n_circ * n_axial of one film
inline constexpr long kMaxDrillHoles = 8;         ///< radial holes of a floating ring
inline constexpr long kMaxBalls = 200;            ///< balls of one ball bearing
inline constexpr long kMaxModalSpeeds = 100000;   ///< speeds of a Campbell diagram or response curve
inline constexpr long kMaxModes = 1000;           ///< modes per speed
inline constexpr long kMaxBdfOrder = 5;           ///< CVODE's BDF orders go from 1 to 5
inline constexpr long kMaxSteps = 1000000000;     ///< solver.max_steps per output interval
inline constexpr long kMaxSpectrogramSegment = 1 << 24;  ///< samples of one spectrogram segment

}  // namespace turbodyn::limits
