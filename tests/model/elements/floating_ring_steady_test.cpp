// Steady operating points of a floating-ring bearing (model/elements/floating_ring_steady.h) against the Petroff
// balance, and the balances they solve.
#include "model/elements/floating_ring_steady.h"

#include <cmath>

#include <gtest/gtest.h>

#include "model/rotor/modal.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::reference_ring;

TEST(FloatingRingSteady, UnloadedCentredRingTurnsAtThePetroffRatio) {
  // No load, no weight, no feed: both films centred, the ring at the Petroff ratio
  // 1 / (1 + (B_o/B_i)(D_o/D_i)^3 (C_i/C_o)) = 0.3131 of the reference ring (docs/references.md §4).
  constexpr double kPetroffTolerance = 0.01;  // as FloatingRing.CentredRingSpeedFollowsThePetroffBalance
  FloatingRingSpec f = reference_ring();
  f.supply_pressure = 0.0;
  f.feed_hole_diameter = 0.0;
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 0.0);
  const FloatingRingSteady steady(e);
  for (double rpm : {30000.0, 150000.0}) {
    const FloatingRingOperatingPoint p = steady.solve(rpm * 2 * M_PI / 60, Eigen::Vector2d::Zero());
    EXPECT_NEAR(p.ring_speed / p.speed / 0.3131, 1.0, kPetroffTolerance) << rpm;
    EXPECT_LT(p.inner_eccentricity, 1e-6) << rpm;
    EXPECT_LT(p.outer_eccentricity, 1e-6) << rpm;
    // The Petroff powers of the centred films at the ring speed found.
    const double eta = oil.viscosity_at(oil.temperature), W = p.speed, w = p.ring_speed;
    const double pi = eta * M_PI * std::pow(f.inner_diameter, 3) * f.inner_length * (W - w) * (W - w) /
                      (4 * f.inner_clearance);
    const double po = eta * M_PI * std::pow(f.outer_diameter, 3) * f.outer_length * w * w / (4 * f.outer_clearance);
    EXPECT_NEAR(p.inner_power / pi, 1.0, kPetroffTolerance) << rpm;
    EXPECT_NEAR(p.outer_power / po, 1.0, kPetroffTolerance) << rpm;
  }
}

TEST(FloatingRingSteady, LoadedPointBalancesForcesTorqueAndHeat) {
  // At the point the journal carries the load, the ring is at rest and turns steadily, and (thermal films) the
  // heat dissipated leaves by oil and conduction; both films damp, and the outer one is stiff along the load (the
  // lightly loaded inner film is nearly all cross-coupling: its direct stiffness may have either sign).
  OilSpec oil;
  FloatingRingSpec f = reference_ring();
  f.drill_holes = 4;
  f.drill_hole_diameter = 0.002;
  f.thermal.model = FilmThermal::Bulk;
  derive_ring_thermal(f, oil);
  const FloatingRingElement e("test", f, oil, 0, 9.81);
  const FloatingRingSteady steady(e);
  const Eigen::Vector2d load(0.0, -5.0);
  const std::vector<FloatingRingOperatingPoint> pts =
      steady.sweep({50000 * 2 * M_PI / 60, 100000 * 2 * M_PI / 60, 150000 * 2 * M_PI / 60}, load);
  for (const FloatingRingOperatingPoint& p : pts) {
    EXPECT_NEAR(p.inner_power + p.outer_power, p.heat_to_oil + p.heat_conducted,
                1e-6 * (p.inner_power + p.outer_power));
    EXPECT_GT(p.inner_temperature, p.outer_temperature);
    EXPECT_GT(p.outer_temperature, oil.temperature);
    EXPECT_GT(p.k_outer(1, 1), 0.0);
    EXPECT_GT(p.c_inner(1, 1), 0.0);
    EXPECT_GT(p.c_outer(1, 1), 0.0);
  }
  // Hotter inner films as the speed rises: the ratio falls (isothermal films rise towards the Petroff ratio).
  EXPECT_LT(pts[2].ring_speed / pts[2].speed, pts[0].ring_speed / pts[0].speed);
}

TEST(FloatingRingModal, RingOnAStiffOuterFilmLeavesTheJournalOnItsInnerFilm) {
  // The modal analysis's ring coordinates: a ring of negligible mass in an outer film 1e4 times stiffer (and more
  // damping) than its inner film passes the inner film on to the housing, so the rotor's modes are those on linear
  // bearings with the inner film's coefficients.
  constexpr double kTolerance = 1e-3;  // the series outer film changes the support by 1e-4
  const Rotor linear = testing::load_rotor("reference_linear.toml");
  Rotor rings = linear;
  rings.bearings.clear();
  for (const LinearBearing& b : linear.bearings) {
    FloatingRingLinearisation r;
    r.name = b.name;
    r.node = b.node;
    r.ring_mass = 1e-6;
    r.films = [b](double speed, Eigen::Matrix2d& ki, Eigen::Matrix2d& ci, Eigen::Matrix2d& ko, Eigen::Matrix2d& co) {
      b.coefficients(speed, ki, ci);
      ko = 1e4 * ki;
      co = 1e4 * ci;
    };
    rings.rings.push_back(r);
  }
  for (double speed : {0.0, 5000.0, 15000.0}) {
    ModalOptions o;
    o.n_modes = 6;
    const ModalResult a = modal_analysis(linear, speed, o), b = modal_analysis(rings, speed, o);
    ASSERT_EQ(a.modes.size(), b.modes.size()) << speed;
    for (std::size_t i = 0; i < a.modes.size(); ++i) {
      EXPECT_NEAR(b.modes[i].frequency / a.modes[i].frequency, 1.0, kTolerance) << speed << " mode " << i;
      EXPECT_NEAR(b.modes[i].damping_ratio, a.modes[i].damping_ratio, kTolerance) << speed << " mode " << i;
      EXPECT_EQ(b.modes[i].whirl, a.modes[i].whirl) << speed << " mode " << i;
    }
  }
}

}  // namespace
}  // namespace turbodyn
