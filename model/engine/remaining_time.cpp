#include "model/engine/remaining_time.h"

#include <algorithm>
#include <cmath>

namespace turbodyn {

RemainingTimeEstimate::RemainingTimeEstimate(const SpeedFunction& speed, double t_start, double t_end,
                                             double exponent)
    : speed_(speed), t_start_(t_start), t_end_(t_end), p_(exponent) {
  double top = 0.0;
  constexpr int kSamples = 256;
  for (int i = 0; i <= kSamples; ++i)
    top = std::max(top, std::abs(speed_.speed(t_start_ + (t_end_ - t_start_) * i / kSamples)));
  s0_ = top > 0.0 ? 0.02 * top : 1.0;
}

double RemainingTimeEstimate::cost_integral(double t0, double t1) const {
  if (!(t1 > t0)) return 0.0;
  constexpr int kIntervals = 64;  // even
  const double h = (t1 - t0) / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double w = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += w * std::pow(std::abs(speed_.speed(t0 + i * h)) + s0_, p_);
  }
  return sum * h / 3.0;
}

double RemainingTimeEstimate::update(double t, double wall) {
  if (t >= t_end_) return 0.0;
  if (!(t > t_start_) || !(wall > 0.0)) return 0.0;
  times_.push_back(t);
  walls_.push_back(wall);
  // The simulated time at half the wall time so far (linear interpolation in the history): the recent half of
  // the cost is the one that says most about the cost to come.
  const double half_wall = 0.5 * wall;
  double t_mid = t_start_;
  for (std::size_t i = 0; i < walls_.size(); ++i) {
    if (walls_[i] >= half_wall) {
      const double w0 = i > 0 ? walls_[i - 1] : 0.0, t0 = i > 0 ? times_[i - 1] : t_start_;
      t_mid = t0 + (times_[i] - t0) * (half_wall - w0) / std::max(walls_[i] - w0, 1e-300);
      break;
    }
  }
  const bool split = t_mid > t_start_ && t_mid < t;
  const double cost_so_far = split ? cost_integral(t_mid, t) : cost_integral(t_start_, t);
  const double wall_so_far = split ? wall - half_wall : wall;
  if (!(cost_so_far > 0.0)) return 0.0;
  return wall_so_far / cost_so_far * cost_integral(t, t_end_);
}

}  // namespace turbodyn
