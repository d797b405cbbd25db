// The run-up's time-left estimate: exact for a cost of the model's form, the plain proportion at constant speed,
// and the recent cost rate counts.
#include "model/engine/remaining_time.h"

#include <cmath>

#include <gtest/gtest.h>

namespace turbodyn {
namespace {

SpeedFunction ramp(double start, double end, double duration) {
  SpeedProfile p;
  p.kind = SpeedProfile::Kind::Ramp;
  p.start = start;
  p.end = end;
  p.duration = duration;
  return SpeedFunction(p);
}

TEST(RemainingTime, ForACostOfTheModelsFormItPredictsTheRestOfTheRamp) {
  // A run whose wall cost per simulated second is 40 sqrt((|Omega| + s0) / 15708 rad/s), reported every 0.02 s of
  // simulated time: the time left is exact to the interpolation in the history, early in the ramp as well as late.
  // "Wall so far times the fraction left" would be short by a factor of 2.8 at t = 0.4 s.
  const SpeedFunction speed = ramp(0.0, 15708.0, 4.0);
  RemainingTimeEstimate estimate(speed, 0.0, 4.0);
  const double a = 40.0 / std::sqrt(15708.0);
  const auto wall = [&](double t) { return a * estimate.cost_integral(0.0, t); };
  const double total = wall(4.0);
  for (int k = 1; k < 200; ++k) {
    const double t = 0.02 * k;
    const double left = estimate.update(t, wall(t));
    if (k == 20 || k == 100 || k == 180) {
      EXPECT_NEAR(left, total - wall(t), 5e-3 * (total - wall(t))) << "at t " << t;
      if (k == 20) { EXPECT_GT((total - wall(t)) / (wall(t) * (4.0 - t) / t), 2.8); }
    }
  }
}

TEST(RemainingTime, AtConstantSpeedItIsTheProportionLeft) {
  const SpeedFunction speed = ramp(1000.0, 1000.0, 2.0);
  RemainingTimeEstimate estimate(speed, 0.0, 2.0);
  estimate.update(0.25, 10.0);
  EXPECT_NEAR(estimate.update(0.5, 20.0), 60.0, 1e-9);
  EXPECT_EQ(estimate.update(2.0, 80.0), 0.0);
}

TEST(RemainingTime, TheRecentCostRateCounts) {
  // Constant speed; the run cost 10 s per simulated second up to t = 1 and 20 s after (a whirl set in). At t = 2
  // (wall 30 s) the second half of the wall time, 15 s, covered t = 1.25 ... 2: 20 s per simulated second, so
  // 2 simulated seconds left take 40 s. The proportion would say 30 s.
  const SpeedFunction speed = ramp(1000.0, 1000.0, 4.0);
  RemainingTimeEstimate estimate(speed, 0.0, 4.0);
  double left = 0.0;
  for (int k = 1; k <= 40; ++k) {
    const double t = 0.05 * k;
    left = estimate.update(t, t <= 1.0 ? 10.0 * t : 10.0 + 20.0 * (t - 1.0));
  }
  EXPECT_NEAR(left, 40.0, 1e-9);
}

}  // namespace
}  // namespace turbodyn
