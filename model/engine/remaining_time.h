// How long a run-up still needs: an estimate from the wall time it has cost so far against the rotor speed.
//
// The cost of one simulated second grows with the rotor speed (higher frequencies, more steps), so "wall time so
// far times the fraction left" is far too low early in a ramp. The model: wall cost per simulated second
// c(t) = a s(t)^p with s = |Omega| + s0 (s0 = 2 % of the largest speed of the profile, so that the start does not
// cost nothing). p is chosen so that the model splits the wall time so far between the first and the second half
// of it as the run did (bisection on p in [0, 2]); a is fitted to the cost of the second half, the recent one.
// The time left is then a times the integral of s^p over the rest of the profile.
#pragma once

#include <vector>

#include "model/engine/speed_profile.h"

namespace turbodyn {

class RemainingTimeEstimate {
 public:
  /// The run integrates the profile `speed` from t_start to t_end (s).
  RemainingTimeEstimate(const SpeedFunction& speed, double t_start, double t_end);

  /// Records that the run has reached simulated time t after `wall` seconds of wall time and returns the wall
  /// seconds it still needs (0 at or after t_end). Reports must come with increasing t and wall.
  double update(double t, double wall);

  /// The exponent p of the last estimate.
  double exponent() const { return p_; }

  /// Integral of (|Omega| + s0)^p over [t0, t1] (s (rad/s)^p), Simpson's rule on 64 intervals.
  double cost_integral(double t0, double t1, double p) const;

 private:
  const SpeedFunction& speed_;
  double t_start_, t_end_, s0_ = 0.0;
  double p_ = 0.5;
  std::vector<double> times_, walls_;
};

}  // namespace turbodyn
