// The journal-bearing force element against the short-bearing (Ocvirk) forces, and the Vogel viscosity.
#include "model/elements/journal_bearing_element.h"

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
