// The journal-bearing force element: the shaft's DOFs mapped into the film and the film's force and moment back.
#include "model/elements/journal_bearing_element.h"

#include <cmath>

#include <gtest/gtest.h>

namespace turbodyn {
namespace {

JournalBearingSpec short_bearing_spec() {
  JournalBearingSpec j;
  j.diameter = 0.010;
  j.length = 0.0025;  // L/D = 1/4: close to the short-bearing limit
  j.clearance = 15e-6;
  j.n_circ = 90;
  j.n_axial = 16;
  return j;
}

TEST(JournalBearing, EccentricJournalAgainstTheShortBearingForces) {
  // Ocvirk short-bearing forces (validation-references.md §2) with the element's mapping of the shaft DOFs: a
  // journal displaced in +x and spinning about +z is pushed back (-x) and sideways in the direction of rotation
  // (+y), the cross-coupled force that drives oil whirl.
  OilSpec oil;
  oil.viscosity = 0.0108;
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

TEST(JournalBearing, TiltedJournalFeelsARestoringMoment) {
  // theta_y > 0 tilts the journal axis towards +x at +z (dx/dz = theta_y): the film pushes that end back, a
  // negative moment about y. theta_x > 0 tilts it towards -y at +z: pushed back in +y there, M_x = -z F_y < 0.
  // Both oppose the tilt.
  OilSpec oil;
  oil.viscosity = 0.0108;
  const JournalBearingSpec j = short_bearing_spec();
  const JournalBearingElement e("test", j, oil, 0);
  auto ws = e.make_workspace();
  const SpinState s{0.0, 5000.0, 0.0, 0.0};
  const double tilt = 0.5 * j.clearance / (0.5 * j.length);  // ends at half the clearance
  const double v[4] = {0, 0, 0, 0};
  double f[4] = {0, 0, 0, 0};
  const double qy[4] = {0, 0, 0, tilt};
  e.calc_and_add_forces(s, qy, v, nullptr, *ws, f, nullptr);
  EXPECT_LT(f[3], 0.0);
  double g[4] = {0, 0, 0, 0};
  const double qx[4] = {0, 0, tilt, 0};
  e.calc_and_add_forces(s, qx, v, nullptr, *ws, g, nullptr);
  EXPECT_LT(g[2], 0.0);
  // Axisymmetric film: the same restoring moment turned by 90 degrees (to the solver's tolerance).
  EXPECT_NEAR(g[2], f[3], 1e-3 * std::abs(f[3]));
}

TEST(JournalBearing, OilViscosityFromTheVogelEquation) {
  // reference-turbocharger.md / validation-references.md §7: SAE 30 Vogel fit, 90.3 mPa s at 40 degC,
  // 10.75 mPa s at 90 degC, 8.16 mPa s at 100 degC (printed to 3-4 digits).
  const OilSpec oil;
  EXPECT_NEAR(oil.viscosity_at(273.15 + 40.0) / 90.3e-3, 1.0, 2e-3);
  EXPECT_NEAR(oil.viscosity_at(273.15 + 90.0) / 10.75e-3, 1.0, 2e-3);
  EXPECT_NEAR(oil.viscosity_at(273.15 + 100.0) / 8.16e-3, 1.0, 2e-3);
}

TEST(JournalBearing, ClosingFilmIsAnErrorNotACrash) {
  OilSpec oil;
  const JournalBearingElement e("compressor", short_bearing_spec(), oil, 0);
  auto ws = e.make_workspace();
  const double q[4] = {20e-6, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  double f[4] = {0, 0, 0, 0};
  try {
    e.calc_and_add_forces(SpinState{0.1, 100.0, 0.0, 0.0}, q, v, nullptr, *ws, f, nullptr);
    FAIL() << "no error";
  } catch (const std::runtime_error& err) {
    EXPECT_NE(std::string(err.what()).find("compressor"), std::string::npos) << err.what();
  }
}

}  // namespace
}  // namespace turbodyn
