#include "model/engine/remaining_time.h"

#include <algorithm>
#include <cmath>

namespace turbodyn {

namespace {

constexpr double kDefaultExponent = 0.5;  // before there is history to fit: cost ~ sqrt(speed)
constexpr double kMaxExponent = 2.0;

}  // namespace

RemainingTimeEstimate::RemainingTimeEstimate(const SpeedFunction& speed, double t_start, double t_end)
    : speed_(speed), t_start_(t_start), t_end_(t_end) {
  double top = 0.0;
  constexpr int kSamples = 256;
  for (int i = 0; i <= kSamples; ++i)
    top = std::max(top, std::abs(speed_.speed(t_start_ + (t_end_ - t_start_) * i / kSamples)));
  s0_ = top > 0.0 ? 0.02 * top : 1.0;
}

double RemainingTimeEstimate::cost_integral(double t0, double t1, double p) const {
  if (!(t1 > t0)) return 0.0;
  constexpr int kIntervals = 64;  // even
  const double h = (t1 - t0) / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double w = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += w * std::pow(std::abs(speed_.speed(t0 + i * h)) + s0_, p);
  }
  return sum * h / 3.0;
}

double RemainingTimeEstimate::update(double t, double wall) {
  if (t >= t_end_) return 0.0;
  if (!(t > t_start_) || !(wall > 0.0)) return 0.0;
  times_.push_back(t);
  walls_.push_back(wall);
  // The simulated time at half the wall time so far (linear interpolation in the history).
  const double half_wall = 0.5 * wall;
  double t_mid = t_start_;
  for (std::size_t i = 0; i < walls_.size(); ++i) {
    if (walls_[i] >= half_wall) {
      const double w0 = i > 0 ? walls_[i - 1] : 0.0, tt0 = i > 0 ? times_[i - 1] : t_start_;
      t_mid = tt0 + (times_[i] - tt0) * (half_wall - w0) / std::max(walls_[i] - w0, 1e-300);
      break;
    }
  }
  // p: the model's share of the first half, I(t_start, t_mid) / I(t_start, t), equals one half. The share falls
  // as p grows when the speed rises; clamp p to [0, kMaxExponent] where no p matches.
  if (t_mid > t_start_ && t_mid < t) {
    const auto share = [&](double p) { return cost_integral(t_start_, t_mid, p) / cost_integral(t_start_, t, p); };
    const double s_lo = share(0.0), s_hi = share(kMaxExponent);
    if ((s_lo - 0.5) * (s_hi - 0.5) <= 0.0) {
      double lo = 0.0, hi = kMaxExponent;
      for (int i = 0; i < 50; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((share(mid) - 0.5) * (s_lo - 0.5) > 0.0 ? lo : hi) = mid;
      }
      p_ = 0.5 * (lo + hi);
    } else {
      p_ = std::abs(s_lo - 0.5) < std::abs(s_hi - 0.5) ? 0.0 : kMaxExponent;
    }
  } else {
    p_ = kDefaultExponent;
  }
  // a from the recent half, then the rest of the profile.
  const double recent = t_mid > t_start_ && t_mid < t ? cost_integral(t_mid, t, p_) : cost_integral(t_start_, t, p_);
  const double recent_wall = t_mid > t_start_ && t_mid < t ? wall - half_wall : wall;
  if (!(recent > 0.0)) return 0.0;
  return recent_wall / recent * cost_integral(t, t_end_, p_);
}

}  // namespace turbodyn
