// Squeeze-film damper around a linear bearing: film forces on a centred circular orbit against the short-damper
// closed forms, and sealed ends against the long damper.
#include "model/elements/damper_element.h"

#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "model/engine/integrator.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// A damper land of diameter 20 mm and clearance 50 um, width `length`, on a 90 x 12 grid.
DamperSpec test_damper(double length) {
  DamperSpec d;
  d.enabled = true;
  d.diameter = 0.02;
  d.length = length;
  d.clearance = 50e-6;
  d.ring_mass = 0.015;
  d.n_circ = 90;
  d.n_axial = 12;
  return d;
}

// The film's force on the ring (x, y) of a damper whose ring is at the state z = (x, y, vx, vy), i.e. minus the force
// the element puts on the housing (no centring spring), and the element's eccentricity probe.
std::array<double, 3> film_force_on_ring(const DamperSpec& d, double eta, const double (&z)[4]) {
  LinearBearing b;
  b.name = "test";
  b.table.k = {{{3e7}, {0.0}, {0.0}, {3e7}}};
  b.table.c = {{{0.0}, {0.0}, {0.0}, {0.0}}};
  OilSpec oil;
  oil.viscosity = eta;
  const DamperElement e(b, 0, d, oil, 0.0);
  auto ws = e.make_workspace();
  std::vector<double> out(e.probes().size());
  const double q[2] = {0, 0}, v[2] = {0, 0};
  e.eval_probes(SpinState{}, q, v, z, *ws, out.data());
  // The thinnest film (probe 5) of the untilted damper: c - e.
  EXPECT_NEAR(out[5], d.clearance - std::hypot(z[0], z[1]), 1e-15);
  EXPECT_EQ(e.probes()[5].name, "damper_min_film_thickness");
  return {-out[0], -out[1], out[4]};
}

// Radial damping of the uncavitated open-ended short damper at e = eps c, docs/references.md section 3:
// C_rr = pi eta R L^3 (1 + 2 eps^2) / (c^3 (1 - eps^2)^2.5).
double short_damper_radial_damping(double eta, double R, double L, double c, double eps) {
  return M_PI * eta * R * std::pow(L, 3) * (1 + 2 * eps * eps) / (std::pow(c, 3) * std::pow(1 - eps * eps, 2.5));
}

// Tangential and radial film force on the ring of a damper whose ring runs a centred circular orbit.
struct OrbitForce {
  double radial, tangential, eccentricity;
};
OrbitForce orbit_force(const DamperSpec& d, double eta, double eps, double w) {
  const double c = d.clearance, phase = 0.7, cp = std::cos(phase), sp = std::sin(phase);
  const double z[4] = {eps * c * cp, eps * c * sp, -eps * c * w * sp, eps * c * w * cp};
  const std::array<double, 3> f = film_force_on_ring(d, eta, z);
  return {f[0] * cp + f[1] * sp, -f[0] * sp + f[1] * cp, f[2]};
}

// Radial film force on the ring of a damper whose ring moves along its line of centres at e = eps c with speed edot.
double radial_squeeze_force(const DamperSpec& d, double eta, double eps, double edot) {
  const double c = d.clearance, phase = 0.7, cp = std::cos(phase), sp = std::sin(phase);
  const double z[4] = {eps * c * cp, eps * c * sp, edot * cp, edot * sp};
  const std::array<double, 3> f = film_force_on_ring(d, eta, z);
  return f[0] * cp + f[1] * sp;
}

TEST(Damper, CircularOrbitAgainstTheShortDamperClosedForms) {
  // docs/references.md §3: open-ended short damper, centred circular orbit of radius e = eps c at whirl
  // speed w; pi-film (Swift-Stieber): C_tt = pi eta R L^3 / (2 c^3 (1-eps^2)^1.5), K_rr = 2 eta R L^3 w eps /
  // (c^3 (1-eps^2)^2); tangential force -C_tt eps c w, radial -K_rr eps c. The element transmits these (and the
  // centring spring, zero here) to the housing.
  constexpr double kShortDamperTolerance = 0.05;  // L/D = 0.1 film against the short-damper limit
  DamperSpec d = test_damper(0.002);
  const double eps = 0.4, w = 1000.0, R = 0.01, L = d.length, c = d.clearance, eta = 0.01;
  const OrbitForce f = orbit_force(d, eta, eps, w);  // anywhere on the orbit
  const double Ctt = M_PI * eta * R * std::pow(L, 3) / (2 * std::pow(c, 3) * std::pow(1 - eps * eps, 1.5));
  const double Krr = 2 * eta * R * std::pow(L, 3) * w * eps / (std::pow(c, 3) * std::pow(1 - eps * eps, 2));
  EXPECT_NEAR(f.tangential / (-Ctt * eps * c * w), 1.0, kShortDamperTolerance);
  EXPECT_NEAR(f.radial / (-Krr * eps * c), 1.0, kShortDamperTolerance);
  EXPECT_NEAR(f.eccentricity, eps, 1e-12);
}

TEST(Damper, RadialSqueezeAgainstTheShortDamperClosedForm) {
  // docs/references.md section 3: a ring moving along its line of centres at edot in the uncavitated open-ended short
  // damper meets C_rr = pi eta R L^3 (1 + 2 eps^2) / (c^3 (1 - eps^2)^2.5). Its eps-dependence is what the ball
  // dampers' ring velocity tolerance follows (BallDamperElement::ring_velocity_tolerance_factor).
  // L/D = 0.025: the short-film limit to 0.5 % up to eps = 0.9 (at L/D = 0.1 the film lies 6 % below it at 0.9).
  constexpr double kShortDamperTolerance = 0.01;
  DamperSpec d = test_damper(0.0005);
  d.cavitation = Cavitation::None;
  const double R = 0.01, L = d.length, c = d.clearance, eta = 0.01, edot = 1e-3;
  for (const double eps : {0.3, 0.6, 0.9}) {
    const double Crr = short_damper_radial_damping(eta, R, L, c, eps);
    EXPECT_NEAR(radial_squeeze_force(d, eta, eps, edot) / (-Crr * edot), 1.0, kShortDamperTolerance) << eps;
  }
}

TEST(Damper, ACentralFeedGrooveSplitsTheLandIntoTwoShortDampersAndPushesTheRingNowhere) {
  // A full circumferential groove at mid-width held at the supply pressure cuts the land into two lands of
  // (L - w)/2, each a short damper: C_rr = 2 x 2 pi eta R ((L - w)/2)^3 (...), (1 - w/L)^3 / 4 of the ungrooved
  // land's (San Andres, Modern Lubrication Theory, Notes 13: a central feed groove acting as a pressure source). The
  // supply pressure then falls linearly from the groove to the ends, the same all round, and adds no force
  // (uncavitated film), where the same pressure in a feed hole at the top pushes the ring down.
  constexpr double kShortDamperTolerance = 0.01;  // L/D = 0.025, each land 0.0125: the short-film limit
  DamperSpec d = test_damper(0.0005);
  d.cavitation = Cavitation::None;
  d.n_axial = 25;  // a row of nodes at mid-width: the groove narrower than a grid step fixes that row alone
  const double R = 0.01, L = d.length, c = d.clearance, eta = 0.01, edot = 1e-3, eps = 0.5;
  const double Crr = short_damper_radial_damping(eta, R, L, c, eps);
  EXPECT_NEAR(radial_squeeze_force(d, eta, eps, edot) / (-Crr * edot), 1.0, kShortDamperTolerance);
  d.feed_groove_width = 0.01 * L;
  d.supply_pressure = 4e5;
  const double grooved_Crr = Crr * std::pow(1.0 - d.feed_groove_width / L, 3) / 4;
  const double error_25 = radial_squeeze_force(d, eta, eps, edot) / (-grooved_Crr * edot) - 1.0;
  EXPECT_NEAR(error_25, 0.0, kShortDamperTolerance);
  // The grooved land's profile kinks at the groove, whose edges the grid's faces are fitted to: the error is -1.35 %,
  // -0.23 % and +0.003 % with 13, 25 and 49 nodes, where the plain land's parabola is exact on any grid.
  DamperSpec fine = d;
  fine.n_axial = 49;
  const double error_49 = radial_squeeze_force(fine, eta, eps, edot) / (-grooved_Crr * edot) - 1.0;
  EXPECT_LT(std::abs(error_49), std::abs(error_25) / 3);
  // The supply pressure keeps the grooved film whole: with Gumbel cavitation it damps as the uncavitated one.
  fine.cavitation = Cavitation::Gumbel;
  EXPECT_NEAR(radial_squeeze_force(fine, eta, eps, edot) / (-grooved_Crr * edot) - 1.0, error_49, 1e-6);
  const double still[4] = {0, 0, 0, 0};
  const std::array<double, 3> grooved = film_force_on_ring(d, eta, still);
  EXPECT_LT(std::hypot(grooved[0], grooved[1]), 1e-9 * d.supply_pressure * 2 * M_PI * R * L);
  d.feed_groove_width = 0.0;
  d.feed_hole_diameter = 0.4 * L;  // at the top (feed_hole_angle pi/2)
  const std::array<double, 3> holed = film_force_on_ring(d, eta, still);
  EXPECT_LT(holed[1], 0.0);  // down
  EXPECT_LT(std::abs(holed[0]), 0.1 * std::abs(holed[1]));  // the hole is smaller than a grid step: its nearest node
}

TEST(Damper, SealedEndsGiveTheLongDamperAndALeakySealLiesBetween) {
  // End seals (end_seal_gap, end_seal_length): a slot in series with each end of the land. Nearly closed (gap
  // 1e-3 c), no oil leaves axially and the full-film damper is the long (infinitely long) damper of the same land:
  // C_tt = 24 pi eta R^3 L / (c^3 (2 + eps^2) sqrt(1 - eps^2)), no radial force (San Andres, Modern Lubrication
  // Theory, Notes 13, full 2-pi film). A seal as wide as the clearance and as long as the land adds the slot's
  // resistance to the land's: the force lies between the open and the closed damper.
  constexpr double kLongDamperTolerance = 0.01;
  DamperSpec d = test_damper(0.006);
  d.cavitation = Cavitation::None;
  const double eps = 0.3, w = 1000.0, R = 0.01, L = d.length, c = d.clearance, eta = 0.01;
  const OrbitForce open = orbit_force(d, eta, eps, w);
  d.end_seal_gap = 1e-3 * c;
  d.end_seal_length = 1e-3;
  const OrbitForce sealed = orbit_force(d, eta, eps, w);
  const double Ctt = 24 * M_PI * eta * std::pow(R, 3) * L / (std::pow(c, 3) * (2 + eps * eps) * std::sqrt(1 - eps * eps));
  EXPECT_NEAR(sealed.tangential / (-Ctt * eps * c * w), 1.0, kLongDamperTolerance);
  EXPECT_LT(std::abs(sealed.radial), 1e-3 * std::abs(sealed.tangential));
  d.end_seal_gap = c;
  d.end_seal_length = L;
  const OrbitForce leaky = orbit_force(d, eta, eps, w);
  EXPECT_LT(std::abs(open.tangential), std::abs(leaky.tangential));
  EXPECT_LT(std::abs(leaky.tangential), std::abs(sealed.tangential));
  // The closed damper damps far more than the open one: the long/short ratio 24 R^2 / L^2 (small eps), ~ 67 here.
  EXPECT_GT(std::abs(sealed.tangential), 20.0 * std::abs(open.tangential));
}

}  // namespace
}  // namespace turbodyn
