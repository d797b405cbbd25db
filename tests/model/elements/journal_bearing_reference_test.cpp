// The journal-bearing force element against the short-bearing (Ocvirk) forces, and the Vogel viscosity.
#include "model/elements/journal_bearing_element.h"

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::short_bearing_spec;

TEST(JournalBearing, EccentricJournalAgainstTheShortBearingForces) {
  // Ocvirk short-bearing forces (docs/references.md §2) with the element's mapping of the shaft DOFs: a
  // journal displaced in +x and spinning about +z is pushed back (-x) and sideways in the direction of rotation
  // (+y), the cross-coupled force that drives oil whirl.
  const OilSpec oil = testing::oil_of_viscosity(0.0108);
  const JournalBearingSpec j = short_bearing_spec();
  const JournalBearingElement e("test", j, oil, 0);
  auto ws = e.make_workspace();
  const double eps = 0.5, omega = 5000.0;
  const double q[4] = {eps * j.clearance, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  double f[4] = {0, 0, 0, 0};
  const SpinState s{0.0, omega, 0.0, 0.0};
  e.calc_and_add_forces(s, q, v, nullptr, *ws, f, nullptr);
  const reynolds::Closed ref = reynolds::short_bearing(oil.viscosity, omega, 0.005, j.length, j.clearance, eps);
  EXPECT_LT(f[0], 0.0);
  EXPECT_GT(f[1], 0.0);
  // L/D = 1/4 is not quite short: the finite bearing carries a little less than the Ocvirk formula.
  constexpr double kShortBearingTolerance = 0.12;
  EXPECT_NEAR(-f[0] / std::abs(ref.radial), 1.0, kShortBearingTolerance);
  EXPECT_NEAR(f[1] / std::abs(ref.tangential), 1.0, kShortBearingTolerance);
  EXPECT_NEAR(f[2], 0.0, 1e-9 * std::abs(f[0]));  // no tilt, no moment
  EXPECT_NEAR(f[3], 0.0, 1e-9 * std::abs(f[0]));
}

TEST(JournalBearing, ACentralFeedGrooveMakesTwoShortBearingsOfTheLands) {
  // A full circumferential groove at mid-width cuts the bearing into two lands of (L - w)/2, each a short bearing
  // with ambient pressure at both its ends (groove unfed): the Ocvirk forces of the two lands, 2 ((L - w)/(2L))^3 of
  // the whole bearing's (docs/references.md §2). Fed at 2 bar with the film kept whole
  // (no cavitation), the groove's pressure, the same all round, adds no force, and each land carries the full
  // Sommerfeld short film: no radial force, twice the half film's tangential one.
  const OilSpec oil = testing::oil_of_viscosity(0.0108);
  JournalBearingSpec j = short_bearing_spec();
  j.length = 0.002;           // L/D = 0.2, each land L/D = 0.08: the short-bearing limit to about 1 %
  j.feed_groove_width = 4e-4;
  j.n_axial = 13;             // the groove holds the middle three rows, each land keeps five
  const double eps = 0.5, omega = 5000.0, land = 0.5 * (j.length - j.feed_groove_width);
  const reynolds::Closed one = reynolds::short_bearing(oil.viscosity, omega, 0.005, land, j.clearance, eps);
  auto forces = [&](const JournalBearingSpec& spec) {
    const JournalBearingElement e("test", spec, oil, 0);
    auto ws = e.make_workspace();
    const double q[4] = {eps * spec.clearance, 0, 0, 0}, v[4] = {0, 0, 0, 0};
    std::array<double, 4> f{};
    e.calc_and_add_forces(SpinState{0.0, omega, 0.0, 0.0}, q, v, nullptr, *ws, f.data(), nullptr);
    return f;
  };
  constexpr double kShortLandTolerance = 0.02;  // on this grid +0.58 % (radial), +0.68 % and +0.66 % (tangential)
  const std::array<double, 4> grooved = forces(j);
  EXPECT_NEAR(-grooved[0] / (2 * one.radial), 1.0, kShortLandTolerance);
  EXPECT_NEAR(grooved[1] / (2 * one.tangential), 1.0, kShortLandTolerance);
  JournalBearingSpec fed = j;
  fed.supply_pressure = 2e5;
  fed.cavitation = Cavitation::None;
  const std::array<double, 4> whole = forces(fed);
  EXPECT_LT(std::abs(whole[0]), 0.01 * std::abs(whole[1]));
  EXPECT_NEAR(whole[1] / (4 * one.tangential), 1.0, kShortLandTolerance);
}

TEST(JournalBearing, OilViscosityFromTheVogelEquation) {
  // docs/reference-machine.md / docs/references.md §7: SAE 30 Vogel fit, 90.3 mPa s at 40 degC,
  // 10.75 mPa s at 90 degC, 8.16 mPa s at 100 degC (printed to 3-4 digits).
  const OilSpec oil;
  EXPECT_NEAR(oil.viscosity_at(273.15 + 40.0) / 90.3e-3, 1.0, 2e-3);
  EXPECT_NEAR(oil.viscosity_at(273.15 + 90.0) / 10.75e-3, 1.0, 2e-3);
  EXPECT_NEAR(oil.viscosity_at(273.15 + 100.0) / 8.16e-3, 1.0, 2e-3);
}

}  // namespace
}  // namespace turbodyn
