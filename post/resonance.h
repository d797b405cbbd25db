#pragma once
// Resonances of a response curve against speed, read the way a rotordynamics engineer reads a Bode plot: the peak,
// the half-power points on either side, and the amplification factor (API RP 684's half-power method).
//
// For a curve y(x), an unbalance response's amplitude against rotor speed, a resonance is a local maximum (x_c, y_c)
// around which the curve falls to y_c / sqrt(2), the half-power level, before it rises above y_c again. Its half-power
// points x_1 < x_c < x_2 are where it crosses that level, and its amplification factor is AF = x_c / (x_2 - x_1).
// For one lightly damped mode AF = 1 / (2 zeta) to first order in the damping ratio zeta (the unbalance response
// of one degree of freedom, e eta^2 / sqrt((1 - eta^2)^2 + (2 zeta eta)^2), has its half-power band 2 zeta x_c wide);
// API 617 bases its required separation margins on it, and calls a response with AF < 2.5 critically damped.
// References: API RP 684 (2nd ed., 2005), "Rotordynamic tutorial: lateral critical speeds, unbalance response,
// stability, train torsionals and rotor balancing"; API Std 617 (7th ed., 2002); docs/references.md.
#include <functional>
#include <limits>
#include <vector>

namespace turbodyn::post {

struct Resonance {
  double speed = 0.0;  ///< x_c, the peak's abscissa (the samples' unit)
  double peak = 0.0;   ///< y_c
  /// Half-power points x_1 < x_c < x_2; NaN on a side where the curve does not fall to y_c / sqrt(2) before the end
  /// of the range (the band is then open there and the amplification factor unknown).
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  /// x_c / (x_2 - x_1); NaN unless both half-power points lie in the range.
  double amplification_factor = std::numeric_limits<double>::quiet_NaN();
  /// true: the peak and the half-power points were found on the curve itself (curve_at), each search stopped where its
  /// bracket is 1e-10 of the speed wide; false: from the samples (a parabola through the three about the peak,
  /// straight lines between samples).
  bool refined = false;
};

/// The resonances of the samples (xs strictly increasing, ys finite and >= 0), lowest speed first: every interior
/// local maximum of the samples around which they fall to the half-power level on at least one side before they rise
/// above the peak (a shoulder inside a larger resonance's band, or a maximum with the band open on both sides, is
/// none). With curve_at (the curve at any x in [xs.front(), xs.back()], e.g. the unbalance response computed anew
/// at that speed), the peak is sought by golden section between the samples beside the peak sample, and each
/// half-power point by bisection between the samples (or the peak) that straddle it, so a resonance narrower than
/// the samples' spacing is measured as well as a wide one. Throws std::invalid_argument for fewer than three
/// samples, sizes that differ, xs not strictly increasing, or a y that is negative or not finite.
std::vector<Resonance> find_resonances(const std::vector<double>& xs, const std::vector<double>& ys,
                                       const std::function<double(double)>& curve_at = {});

}  // namespace turbodyn::post
