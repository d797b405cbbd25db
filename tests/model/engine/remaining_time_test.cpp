// The run-up's time-left estimate: exact for a cost of the model's form, the plain proportion at constant speed.
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

TEST(RemainingTime, RecoversTheCostLawOfARampAndPredictsTheRest) {
  // A run whose wall cost per simulated second is 40 (|Omega| + s0)^p: reported twice a "second" of wall time,
  // the estimate finds p and the time left to a few per cent (the history is sampled, and the split of the wall
  // time interpolated in it), early in the ramp as well as late; "wall so far times the fraction left" would be
  // short by a factor of 1.9 to 36 at t = 0.4 s.
  const SpeedFunction speed = ramp(0.0, 15708.0, 4.0);
  for (double p : {0.3, 1.0, 1.7}) {
    RemainingTimeEstimate estimate(speed, 0.0, 4.0);
    const double a = 40.0 / std::pow(15708.0, p);
    const auto wall = [&](double t) { return a * estimate.cost_integral(0.0, t, p); };
    const double total = wall(4.0);
    double left = 0.0, t_last = 0.0;
    for (double t = 0.02; t < 4.0; t += 0.02) {
      left = estimate.update(t, wall(t));
      t_last = t;
      if (std::abs(t - 0.4) < 1e-9 || std::abs(t - 2.0) < 1e-9) {
        EXPECT_NEAR(estimate.exponent(), p, 2e-2) << "p " << p << " at t " << t;
        EXPECT_NEAR(left, total - wall(t), 3e-2 * (total - wall(t))) << "p " << p << " at t " << t;
      }
    }
    EXPECT_NEAR(left, total - wall(t_last), 1e-2 * total);
  }
}

TEST(RemainingTime, AtConstantSpeedItIsTheProportionLeft) {
  const SpeedFunction speed = ramp(1000.0, 1000.0, 2.0);
  RemainingTimeEstimate estimate(speed, 0.0, 2.0);
  estimate.update(0.25, 10.0);
  EXPECT_NEAR(estimate.update(0.5, 20.0), 60.0, 1e-9);
  EXPECT_EQ(estimate.update(2.0, 80.0), 0.0);
}

TEST(RemainingTime, ACostThatFallsWithSpeedIsClampedToNoGrowth) {
  // Cost per simulated second falling as the speed rises (p < 0) is outside the model: p is clamped to 0 and
  // the estimate is the recent cost rate times the time left.
  const SpeedFunction speed = ramp(0.0, 10000.0, 1.0);
  RemainingTimeEstimate estimate(speed, 0.0, 1.0);
  double left = 0.0;
  for (int i = 1; i <= 50; ++i) {
    const double t = 0.01 * i;
    left = estimate.update(t, 100.0 * std::sqrt(t));  // the rate 50 / sqrt(t) falls
  }
  EXPECT_EQ(estimate.exponent(), 0.0);
  // Recent rate: (100 sqrt(0.5) - 50 sqrt(0.5)) over the simulated time of the second half of the wall time.
  const double t_mid = 0.5 * 0.5 * 0.5;  // wall 100 sqrt(t) reaches half of 100 sqrt(0.5) at t = 0.125
  EXPECT_NEAR(left, 50.0 * std::sqrt(0.5) / (0.5 - t_mid) * 0.5, 1e-3 * left);  // t_mid interpolated
}

}  // namespace
}  // namespace turbodyn
