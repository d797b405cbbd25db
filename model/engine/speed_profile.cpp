#include "model/engine/speed_profile.h"

#include <algorithm>

namespace turbodyn {

SpeedFunction::SpeedFunction(const SpeedProfile& p) {
  if (p.kind == SpeedProfile::Kind::Ramp) {
    times_ = {0.0, p.duration};
    speeds_ = {p.start, p.end};
  } else {
    times_ = p.times;
    speeds_ = p.speeds;
    if (times_.front() > 0.0) {  // constant speed before the first point
      times_.insert(times_.begin(), 0.0);
      speeds_.insert(speeds_.begin(), speeds_.front());
    }
  }
  end_time_ = times_.back();
  angles_.assign(times_.size(), 0.0);
  for (std::size_t i = 1; i < times_.size(); ++i)
    angles_[i] = angles_[i - 1] + 0.5 * (speeds_[i] + speeds_[i - 1]) * (times_[i] - times_[i - 1]);
}

std::size_t SpeedFunction::segment(double t) const {
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  if (it == times_.begin()) return 0;
  return std::min<std::size_t>(static_cast<std::size_t>(it - times_.begin()) - 1, times_.size() - 2);
}

double SpeedFunction::speed(double t) const {
  if (t <= times_.front()) return speeds_.front();
  if (t >= times_.back()) return speeds_.back();
  const std::size_t i = segment(t);
  const double a = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return speeds_[i] + a * (speeds_[i + 1] - speeds_[i]);
}

double SpeedFunction::acceleration(double t) const {
  if (t < times_.front() || t >= times_.back()) return 0.0;
  const std::size_t i = segment(t);
  return (speeds_[i + 1] - speeds_[i]) / (times_[i + 1] - times_[i]);
}

double SpeedFunction::angle(double t) const {
  if (t <= times_.front()) return speeds_.front() * (t - times_.front());
  if (t >= times_.back()) return angles_.back() + speeds_.back() * (t - times_.back());
  const std::size_t i = segment(t);
  const double dt = t - times_[i];
  const double acc = (speeds_[i + 1] - speeds_[i]) / (times_[i + 1] - times_[i]);
  return angles_[i] + speeds_[i] * dt + 0.5 * acc * dt * dt;
}

}  // namespace turbodyn
