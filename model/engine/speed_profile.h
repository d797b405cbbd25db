// The prescribed rotor spin: speed Omega(t), acceleration dOmega/dt and spin angle phi(t) = integral of Omega.
#pragma once

#include <vector>

#include "model/spec/model_spec.h"

namespace turbodyn {

class SpeedFunction {
 public:
  explicit SpeedFunction(const SpeedProfile& profile);

  double speed(double t) const;         ///< Omega in rad/s
  double acceleration(double t) const;  ///< dOmega/dt in rad/s^2
  double angle(double t) const;         ///< phi in rad, phi(0) = 0, exact integral of speed()
  double duration() const { return end_time_; }  ///< s

 private:
  // Piecewise-linear speed through (times_[i], speeds_[i]); constant after the last point.
  std::vector<double> times_, speeds_, angles_;
  double end_time_ = 0.0;
  std::size_t segment(double t) const;
};

}  // namespace turbodyn
