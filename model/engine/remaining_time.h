// How long a run-up still needs: an estimate from the wall time it has cost so far against the rotor speed.
//
// The cost of one simulated second grows with the rotor speed (higher frequencies, more steps), so "wall time so
// far times the fraction left" is far too low early in a ramp. The model: wall cost per simulated second
// c(t) = a s(t)^p with s = |Omega| + s0 (s0 = 2 % of the largest speed of the profile, so that the start does not
// cost nothing) and p = 0.5; a is fitted to the recent cost, the second half of the wall time so far. The time
// left is a times the integral of s^p over the rest of the profile. p = 0.5 was chosen on the full 4-s run-ups of
// variants I and II (bench/README.md): from a quarter of the run on, the estimate is within 0.9-1.5x of the time
// the runs really took, where the proportion gives 0.2-0.9x. Fitting p to the history instead reacted to every
// onset of whirl and overshot by 2-5x.
#pragma once

#include <vector>

#include "model/engine/speed_profile.h"

namespace turbodyn {

class RemainingTimeEstimate {
 public:
  /// The run integrates the profile `speed` from t_start to t_end (s); exponent: p of the cost model.
  RemainingTimeEstimate(const SpeedFunction& speed, double t_start, double t_end, double exponent = 0.5);

  /// Records that the run has reached simulated time t after `wall` seconds of wall time and returns the wall
  /// seconds it still needs (0 at or after t_end). Reports must come with increasing t and wall.
  double update(double t, double wall);

  /// Integral of (|Omega| + s0)^p over [t0, t1] (s (rad/s)^p), Simpson's rule on 64 intervals.
  double cost_integral(double t0, double t1) const;

 private:
  const SpeedFunction& speed_;
  double t_start_, t_end_, p_, s0_ = 0.0;
  std::vector<double> times_, walls_;
};

}  // namespace turbodyn
