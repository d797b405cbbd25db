#include "post/resonance.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace turbodyn::post {
namespace {

using ::testing::HasSubstr;

// One degree of freedom under unbalance: the amplitude e eta^2 / sqrt((1 - eta^2)^2 + (2 zeta eta)^2) at the speed
// ratio eta = x / wn. Its peak lies at eta^2 = 1 / (1 - 2 zeta^2) with e / (2 zeta sqrt(1 - zeta^2)); its half-power
// points solve, with u = eta^2 and A = 1 / (8 zeta^2 (1 - zeta^2)), (A - 1) u^2 - 2 A (1 - 2 zeta^2) u + A = 0.
struct OneDofUnbalance {
  double wn = 100.0, zeta = 0.05, e = 1e-5;
  double operator()(double x) const {
    const double eta = x / wn;
    return e * eta * eta / std::hypot(1.0 - eta * eta, 2.0 * zeta * eta);
  }
  double peak_speed() const { return wn / std::sqrt(1.0 - 2.0 * zeta * zeta); }
  double peak() const { return e / (2.0 * zeta * std::sqrt(1.0 - zeta * zeta)); }
  double half_power(int side) const {
    const double a = 1.0 / (8.0 * zeta * zeta * (1.0 - zeta * zeta)), b = a * (1.0 - 2.0 * zeta * zeta);
    return wn * std::sqrt((b + side * std::sqrt(b * b - a * (a - 1.0))) / (a - 1.0));
  }
};

std::vector<double> speeds_over(double from, double to, int n) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = from + (to - from) * i / (n - 1);
  return x;
}

std::vector<double> sampled_curve(const std::vector<double>& xs, const std::function<double(double)>& f) {
  std::vector<double> y;
  for (double x : xs) y.push_back(f(x));
  return y;
}

TEST(Resonances, HalfPowerPointsAndAmplificationFactorOfOneDegreeOfFreedomAreItsClosedForm) {
  // 201 speeds up to three times the natural frequency (a step of 1.5 % of it): the band is 10 steps wide at
  // zeta = 0.05, a tenth of a step at 1e-4, which only the curve itself resolves.
  const std::vector<double> xs = speeds_over(0.0, 300.0, 201);
  for (const double zeta : {0.1, 0.05, 0.01, 0.002, 1e-4}) {
    const OneDofUnbalance c{100.0, zeta, 1e-5};
    const std::vector<Resonance> r = find_resonances(xs, sampled_curve(xs, c), c);
    ASSERT_EQ(r.size(), 1u) << zeta;
    const double lower = c.half_power(-1), upper = c.half_power(+1);
    EXPECT_TRUE(r[0].refined);
    EXPECT_NEAR(r[0].speed, c.peak_speed(), 1e-7 * c.wn) << zeta;  // the curve is flat at its peak
    EXPECT_NEAR(r[0].peak, c.peak(), 1e-12 * c.peak()) << zeta;
    EXPECT_NEAR(r[0].lower, lower, 1e-9 * c.wn) << zeta;
    EXPECT_NEAR(r[0].upper, upper, 1e-9 * c.wn) << zeta;
    const double af = c.peak_speed() / (upper - lower);
    EXPECT_NEAR(r[0].amplification_factor, af, 1e-6 * af) << zeta;
    // The first-order reading AF = 1 / (2 zeta) (how API RP 684 relates it to the damping): 2 zeta AF = 1 - 4 zeta^2
    // nearly (0.959 at zeta = 0.1, 0.990 at 0.05).
    EXPECT_NEAR(r[0].amplification_factor * 2.0 * zeta, 1.0, 4.1 * zeta * zeta + 1e-5) << zeta;
  }
  // From the samples alone: a band of 10 steps to 1 % (straight lines between the samples widen it, -0.6 %).
  const OneDofUnbalance wide{100.0, 0.05, 1e-5};
  const std::vector<Resonance> r = find_resonances(xs, sampled_curve(xs, wide));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_FALSE(r[0].refined);
  const double af = wide.peak_speed() / (wide.half_power(1) - wide.half_power(-1));
  EXPECT_NEAR(r[0].amplification_factor, af, 0.01 * af);
  EXPECT_NEAR(r[0].speed, wide.peak_speed(), 0.002 * wide.wn);
}

TEST(Resonances, TwoModesAreTwoResonancesAndAShoulderOrAnOpenBandIsNoAmplificationFactor) {
  // Two well separated modes (amplitudes added): two resonances, each as the curve read on 200,001 samples has it,
  // and near 1 / (2 zeta) of its mode (the other mode's flank lifts the second's band: 6 % wider).
  const OneDofUnbalance first{100.0, 0.02, 1e-5}, second{230.0, 0.03, 1e-5};
  auto both = [&](double x) { return first(x) + second(x); };
  const std::vector<double> xs = speeds_over(10.0, 400.0, 157), dense = speeds_over(10.0, 400.0, 200001);
  const std::vector<Resonance> r = find_resonances(xs, sampled_curve(xs, both), both);
  const std::vector<Resonance> fine = find_resonances(dense, sampled_curve(dense, both));
  ASSERT_EQ(r.size(), 2u);
  ASSERT_EQ(fine.size(), 2u);
  for (int m = 0; m < 2; ++m) {
    EXPECT_NEAR(r[m].speed, fine[m].speed, 1e-4) << m;
    EXPECT_NEAR(r[m].lower, fine[m].lower, 1e-5) << m;
    EXPECT_NEAR(r[m].upper, fine[m].upper, 1e-5) << m;
  }
  EXPECT_NEAR(r[0].amplification_factor, 1.0 / (2.0 * 0.02), 0.03 / (2.0 * 0.02));
  EXPECT_NEAR(r[1].amplification_factor, 1.0 / (2.0 * 0.03), 0.1 / (2.0 * 0.03));

  // The range ends inside the band: the peak and its lower half-power point, no factor.
  const OneDofUnbalance c{100.0, 0.05, 1e-5};
  const std::vector<double> short_range = speeds_over(0.0, 103.0, 104);
  const std::vector<Resonance> open = find_resonances(short_range, sampled_curve(short_range, c), c);
  ASSERT_EQ(open.size(), 1u);
  EXPECT_NEAR(open[0].lower, c.half_power(-1), 1e-9 * c.wn);
  EXPECT_TRUE(std::isnan(open[0].upper));
  EXPECT_TRUE(std::isnan(open[0].amplification_factor));

  // Heavily damped (zeta = 0.5): the response never falls to 1/sqrt(2) of its peak above it (it tends to e, 0.87 of
  // the peak): a resonance without a factor, which API 617 calls critically damped.
  const OneDofUnbalance damped{100.0, 0.5, 1e-5};
  const std::vector<double> xs2 = speeds_over(0.0, 1000.0, 501);
  const std::vector<Resonance> d = find_resonances(xs2, sampled_curve(xs2, damped), damped);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_FALSE(std::isnan(d[0].lower));
  EXPECT_TRUE(std::isnan(d[0].upper));

  // A shoulder on the flank of a larger resonance (it does not fall to its own half-power level before the curve
  // rises above it) and a monotone curve: none.
  const std::vector<double> xs3{1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0};
  EXPECT_EQ(find_resonances(xs3, {0.1, 0.3, 0.32, 0.31, 0.6, 1.0, 0.6, 0.3, 0.1}).size(), 1u);
  EXPECT_NEAR(find_resonances(xs3, {0.1, 0.3, 0.32, 0.31, 0.6, 1.0, 0.6, 0.3, 0.1})[0].speed, 6.0, 1e-12);
  EXPECT_TRUE(find_resonances(xs3, {1, 2, 3, 4, 5, 6, 7, 8, 9}).empty());
}

TEST(Resonances, BadSamplesAreRefusedWithTheReason) {
  auto message = [](const std::vector<double>& x, const std::vector<double>& y) -> std::string {
    try {
      find_resonances(x, y);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_THAT(message({1, 2, 3}, {1, 2}), HasSubstr("3 speeds but 2 amplitudes"));
  EXPECT_THAT(message({1, 2}, {1, 2}), HasSubstr("at least three"));
  EXPECT_THAT(message({1, 3, 2}, {1, 2, 3}), HasSubstr("increasing (sample 2)"));
  EXPECT_THAT(message({1, 2, 3}, {1, -2, 3}), HasSubstr("amplitude 1 is negative"));
  EXPECT_THAT(message({1, 2, 3}, {1, NAN, 3}), HasSubstr("amplitude 1"));
}

}  // namespace
}  // namespace turbodyn::post
