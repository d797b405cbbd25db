// Reynolds film solver (model/films/reynolds.h): exact discrete properties (invariances, balances), the cavitation
// models, holes, agreement with independent solvers, convergence order, bad input and warm starts.
// The published tables and closed forms are in reynolds_reference_test.cpp; docs/reynolds.md explains both.
#include "model/films/reynolds.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>
#include <Eigen/SparseLU>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/reynolds_fixtures.h"

namespace turbodyn::reynolds {
namespace {

using ::testing::HasSubstr;
using namespace turbodyn::reynolds::testing;

TEST(GridConvergence, SecondOrderUnderRefinement) {
  // Both steps halved (n_circ doubled, n_axial + 1 doubled), L/D = 1, eps = 0.6. Second-order finite volumes with
  // the loads' Euler-Maclaurin end terms. Full film: observed order p = log2((F_h - F_h/2) / (F_h/2 - F_h/4)) = 2
  // within 0.2. Swift-Stieber: the free boundary's position between grid lines makes the error per halving irregular
  // (ratios 3.1 and 5.0 here; p from three grids 1.4 on the coarsest, 2.0 and 1.8 on finer ones), so its mean order
  // over two halvings, against a fourth grid, is checked: 2 within 0.3.
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    std::vector<double> W;
    for (const int k : {2, 4, 8, 16}) {
      FilmSolver solver(plain(1.0, 24 * k, 6 * k - 1), kEta, with(cav));
      const FilmResult r = solve_ok(solver, journal(0.6));
      W.push_back(std::hypot(r.fx, r.fy));
    }
    if (cav == Cavitation::None) {
      EXPECT_NEAR(std::log2((W[0] - W[1]) / (W[1] - W[2])), 2.0, 0.2) << to_string(cav);
    } else {
      const double e2 = std::abs(W[0] - W[3]), e4 = std::abs(W[1] - W[3]), e8 = std::abs(W[2] - W[3]);
      EXPECT_LT(e8, e4);
      EXPECT_LT(e4, e2);
      EXPECT_NEAR(0.5 * std::log2(e2 / e8), 2.0, 0.3) << to_string(cav);
    }
  }
}

TEST(Invariance, RotatingTheStateRotatesTheForce) {
  // By a grid step: exact up to the solver; by any angle: up to the discretisation (1 % on 60 x 12 at eps 0.6).
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    FilmSolver solver(plain(0.5), kEta, with(cav));
    FilmState s0 = journal(0.6, 0.2);
    s0.vx = 0.3 * kC * kOmega;
    s0.vy = -0.1 * kC * kOmega;
    const FilmResult r0 = solve_ok(solver, s0);
    for (const double a : {2.0 * kPi / 60 * 7, 1.234}) {
      const double ca = std::cos(a), sa = std::sin(a);
      FilmState s = s0;
      s.ex = ca * s0.ex - sa * s0.ey;
      s.ey = sa * s0.ex + ca * s0.ey;
      s.vx = ca * s0.vx - sa * s0.vy;
      s.vy = sa * s0.vx + ca * s0.vy;
      const FilmResult r = solve_ok(solver, s);
      const double fx = ca * r0.fx - sa * r0.fy, fy = sa * r0.fx + ca * r0.fy, F = std::hypot(r0.fx, r0.fy);
      const double tol = a == 1.234 ? 1e-2 : 1e-9;
      EXPECT_NEAR(r.fx, fx, tol * F) << to_string(cav) << " angle " << a;
      EXPECT_NEAR(r.fy, fy, tol * F) << to_string(cav) << " angle " << a;
      EXPECT_NEAR(r.torque_inner, r0.torque_inner, tol * std::abs(r0.torque_inner));
    }
  }
}

TEST(Invariance, SteadyForceDependsOnlyOnTheSumOfTheSpeeds) {
  // Eq. 24: the surface speeds enter the pressure only as (U1 + U2)/2. The friction torques do depend on the split.
  FilmSolver solver(plain(1.0), kEta, with(Cavitation::Gumbel));
  FilmState s = journal(0.5, 0.4);
  const FilmResult a = solve_ok(solver, s);
  s.omega_inner = 0.3 * kOmega;
  s.omega_outer = 0.7 * kOmega;
  const FilmResult b = solve_ok(solver, s);
  s.omega_inner = -kOmega;
  s.omega_outer = 2.0 * kOmega;
  const FilmResult c = solve_ok(solver, s);
  for (const FilmResult* r : {&b, &c}) {
    EXPECT_NEAR(r->fx, a.fx, 1e-12 * std::abs(a.fx));
    EXPECT_NEAR(r->fy, a.fy, 1e-12 * std::abs(a.fy));
  }
  EXPECT_GT(std::abs(b.torque_inner - a.torque_inner), 0.1 * std::abs(a.torque_inner));
}

TEST(Invariance, ReversedRotationMirrorsTheFilm) {
  // omega -> -omega with the journal on the x axis mirrors the film about the x axis: fx stays, fy changes sign.
  // Checks the upwinding of the mass-conserving model in both directions (supply hole on the x axis).
  FilmGeometry g = plain(1.0, 60, 12);
  g.holes = {Hole{kPi, 0.0, 0.01, 3e5}};
  for (const Cavitation cav : {Cavitation::Gumbel, Cavitation::MassConserving}) {
    FilmSolver solver(g, kEta, with(cav));
    const FilmResult a = solve_ok(solver, journal(0.7, 0.0, kOmega));
    const FilmResult b = solve_ok(solver, journal(0.7, 0.0, -kOmega));
    EXPECT_NEAR(b.fx, a.fx, 1e-9 * std::abs(a.fx)) << to_string(cav);
    EXPECT_NEAR(b.fy, -a.fy, 1e-9 * std::abs(a.fx)) << to_string(cav);
    EXPECT_NEAR(b.flow_ends, a.flow_ends, 1e-9 * a.flow_ends) << to_string(cav);
  }
}

TEST(Invariance, CentredStaticFilmCarriesNoLoad) {
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    FilmSolver solver(plain(1.0), kEta, with(cav));
    FilmResult r = solve_ok(solver, journal(0.0, 0.0, kOmega));  // centred and spinning: uniform gap, no pressure
    EXPECT_EQ(r.fx, 0.0);
    EXPECT_EQ(r.fy, 0.0);
    EXPECT_EQ(r.max_pressure, 0.0);
    r = solve_ok(solver, journal(0.5, 1.0, 0.0));  // eccentric, no speeds
    EXPECT_EQ(r.fx, 0.0);
    EXPECT_EQ(r.fy, 0.0);
  }
}

TEST(Invariance, ShiftingAllPrescribedPressuresShiftsTheField) {
  // Ambient, cavitation and hole pressures raised by the same P0: the field rises by P0 (the operator only sees
  // differences), the film fraction, forces and flows stay. Exercises p_cav != 0 and ambient != 0.
  const double P0 = 0.8e5;
  FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6), h = g;
  g.holes = {Hole{kPi / 2, 0.0, 0.002, 2e5}};
  h.holes = {Hole{kPi / 2, 0.0, 0.002, 2e5 + P0}};
  h.ambient_pressure = h.cavitation_pressure = P0;
  for (const Cavitation cav : {Cavitation::Gumbel, Cavitation::MassConserving}) {
    FilmSolver a(g, 0.0108, with(cav)), b(h, 0.0108, with(cav));
    FilmState s = journal(0.7, 0.3, 10000.0, 15e-6);
    s.sy = 3e-4;
    const FilmResult ra = solve_ok(a, s), rb = solve_ok(b, s);
    const double F = std::hypot(ra.fx, ra.fy);
    EXPECT_NEAR(rb.fx, ra.fx, 1e-9 * F) << to_string(cav);
    EXPECT_NEAR(rb.fy, ra.fy, 1e-9 * F) << to_string(cav);
    EXPECT_NEAR(rb.mx, ra.mx, 1e-9 * F * 0.007) << to_string(cav);
    EXPECT_NEAR(rb.flow_ends, ra.flow_ends, 1e-9 * ra.flow_ends) << to_string(cav);
    EXPECT_EQ(rb.cavitated_fraction, ra.cavitated_fraction) << to_string(cav);
    EXPECT_GT(ra.cavitated_fraction, 0.1);
    for (std::size_t k = 0; k < a.pressure().size(); ++k)
      ASSERT_NEAR(b.pressure()[k], a.pressure()[k] + P0, 1e-9 * ra.max_pressure) << k;
  }
}

TEST(Moments, VanishWithoutTiltAndResistTilt) {
  FilmSolver solver(plain(1.0), kEta, with(Cavitation::Gumbel));
  FilmResult r = solve_ok(solver, journal(0.6, 0.5));
  EXPECT_EQ(r.mx, 0.0);
  EXPECT_EQ(r.my, 0.0);
  // Static tilt of a spinning journal (sx > 0: the journal half at z > 0 is displaced towards +x): the direct moment
  // turns it back (my < 0), the cross-coupled one (like the tangential force) is larger, and the net force is zero.
  FilmState s = journal(0.0);
  s.sx = 0.3 * kC / (2.0 * kR);
  r = solve_ok(solver, s);
  EXPECT_LT(r.my, 0.0);
  EXPECT_LT(r.mx, 0.0);
  EXPECT_NEAR(r.fx, 0.0, 1e-9 * std::abs(r.mx) / kR);
  EXPECT_NEAR(r.fy, 0.0, 1e-9 * std::abs(r.mx) / kR);
  // The same about the other axis, rotated by 90 degrees.
  FilmState s2 = journal(0.0);
  s2.sy = s.sx;
  const FilmResult r2 = solve_ok(solver, s2);
  EXPECT_NEAR(r2.mx, -r.my, 1e-6 * std::abs(r.mx));
  EXPECT_NEAR(r2.my, r.mx, 1e-6 * std::abs(r.mx));
  // Tilting velocity of a non-rotating journal: a pure damping moment against the rate.
  s = FilmState{};
  s.dsx = 0.01;
  r = solve_ok(solver, s);
  EXPECT_LT(r.my, 0.0);
  EXPECT_NEAR(r.mx, 0.0, 1e-9 * std::abs(r.my));
  // Tilting squeeze of a short film (Ocvirk approximation: independent axial lines, h = c): the line at theta sees
  // the squeeze velocity z dsx cos(theta), so 12 eta/c^3 ... p'' = -a z with a = 12 eta dsx cos(theta) / c^3.
  // Full film: p = a z (L^2/4 - z^2) / 6 and M_y = -pi eta R L^5 dsx / (60 c^3). Swift-Stieber along each line: the
  // obstacle problem has its free boundary at z = -L/4 (p = p' = 0 there: 1 - 3u^2 + 2u^3 = 0, u = -1/2), giving
  // M_y = -(27 pi / 2560) eta R L^5 dsx / c^3, 1.27 times the clamped (pi-film) value (our derivation; the
  // translational pi-film forms of docs/references.md §3 assume a velocity uniform along z, where the
  // clamp and the complementarity solution coincide). Tolerance 3 % at L/D = 1/8 (finite length).
  const FilmGeometry g = plain(0.125, 120, 24);
  const double L = g.length, base = kEta * kR * std::pow(L, 5) * s.dsx / (kC * kC * kC);
  FilmSolver narrow(g, kEta, with(Cavitation::Gumbel)), narrow_full(g, kEta, with(Cavitation::None));
  EXPECT_LT(rel(solve_ok(narrow, s).my, -27.0 * kPi / 2560.0 * base), 0.03);
  EXPECT_LT(rel(solve_ok(narrow_full, s).my, -kPi / 60.0 * base), 0.03);
}

TEST(Torques, BalanceOfTheFilm) {
  // The film carries no net torque about the bush axis: T_journal + T_bush = -(e x F)_z (pressure couple of the
  // eccentric journal). Discretisation error well below 0.5 %. On the uniform grid and on one graded towards the
  // ends (SolverOptions::axial_grading; reynolds_graded_test.cpp).
  for (const double grading : {0.0, 0.4}) {
    for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
      FilmSolver solver(plain(1.0), kEta, with(cav, grading));
      const FilmState s = journal(0.5, 0.7);
      const FilmResult r = solve_ok(solver, s);
      const double couple = -(s.ex * r.fy - s.ey * r.fx);
      EXPECT_NEAR(r.torque_inner + r.torque_outer, couple, 5e-3 * std::abs(couple)) << to_string(cav) << grading;
    }
    // Centred (Petroff): T = -eta (omega_i - omega_o) R^3 2 pi L / c on the journal, the opposite on the bush.
    FilmSolver solver(plain(1.0), kEta, with(Cavitation::Gumbel, grading));
    FilmState s = journal(0.0);
    s.omega_outer = 0.25 * kOmega;
    const FilmResult r = solve_ok(solver, s);
    const double petroff = -kEta * 0.75 * kOmega * kR * kR * kR * 2.0 * kPi * (2.0 * kR) / kC;
    EXPECT_NEAR(r.torque_inner, petroff, 1e-12 * std::abs(petroff)) << grading;
    EXPECT_NEAR(r.torque_outer, -petroff, 1e-12 * std::abs(petroff)) << grading;
  }
}

TEST(MassConserving, FullFilmAgreesWithGumbel) {
  // Small eccentricity and a 5-bar supply hole keep the whole film above the cavitation pressure: the three models
  // solve the same linear problem.
  const FilmGeometry g = supplied(5e5, 0.01, kPi / 2);
  FilmSolver none(g, kEta, with(Cavitation::None)), gumbel(g, kEta, with(Cavitation::Gumbel)),
      jfo(g, kEta, with(Cavitation::MassConserving));
  const FilmState s = journal(0.02, 0.3);
  const FilmResult a = solve_ok(none, s), b = solve_ok(gumbel, s), c = solve_ok(jfo, s);
  EXPECT_EQ(c.cavitated_fraction, 0.0);
  EXPECT_GT(*std::min_element(none.pressure().begin(), none.pressure().end()), 0.0);
  for (const FilmResult* r : {&b, &c}) {
    EXPECT_NEAR(r->fx, a.fx, 1e-9 * std::hypot(a.fx, a.fy));
    EXPECT_NEAR(r->fy, a.fy, 1e-9 * std::hypot(a.fx, a.fy));
    EXPECT_NEAR(r->torque_inner, a.torque_inner, 1e-9 * std::abs(a.torque_inner));
    EXPECT_NEAR(r->hole_flows[0], a.hole_flows[0], 1e-9 * a.hole_flows[0]);
  }
  EXPECT_THAT(jfo.film_fraction(), ::testing::Each(1.0));
}

TEST(MassConserving, HighEccentricityLoadCloseToSwiftStieber) {
  // For steadily loaded, adequately supplied bearings the Reynolds (Swift-Stieber) condition predicts rupture well
  // and the load within a few per cent of the mass-conserving JFO theory; the reformation boundary differs
  // (Dowson & Taylor 1979; Elrod 1981; Brewe 1986). Here: supply hole Ø 10 mm at the largest gap, 3 bar: within
  // 2 % (0.4 % seen), with a cavitated zone of partial film.
  constexpr double kTol = 0.02;
  const FilmGeometry g = supplied(3e5);
  FilmSolver gumbel(g, kEta, with(Cavitation::Gumbel)), jfo(g, kEta, with(Cavitation::MassConserving));
  for (const double eps : {0.7, 0.8, 0.9}) {
    const FilmResult a = solve_ok(gumbel, journal(eps)), b = solve_ok(jfo, journal(eps));
    EXPECT_LT(rel(std::hypot(b.fx, b.fy), std::hypot(a.fx, a.fy)), kTol) << "eps " << eps;
    EXPECT_GT(b.cavitated_fraction, 0.3);
    const auto [lo, hi] = std::minmax_element(jfo.film_fraction().begin(), jfo.film_fraction().end());
    EXPECT_GE(*lo, 0.0);
    EXPECT_LT(*lo, 0.9);
    EXPECT_EQ(*hi, 1.0);
  }
}

TEST(MassConserving, ContinuityEndLeakageEqualsSupply) {
  // Steady state: what the holes feed leaves through the ends (exact for the discrete scheme; required 1 %).
  // The Swift-Stieber model does not conserve mass (its cavitated nodes are sources and sinks).
  FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6);
  for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2 + 0.2, 0.0, 0.002, 2e5 + 1e4 * k});
  FilmSolver jfo(g, 0.0108, with(Cavitation::MassConserving));
  FilmState s = journal(0.6, 1.0, 10000.0, 15e-6);
  s.sx = 2e-4;  // tilt: no mid-width symmetry
  s.omega_outer = 3000.0;
  const FilmResult r = solve_ok(jfo, s);
  double supply = 0.0;
  for (const double q : r.hole_flows) supply += q;
  EXPECT_GT(r.cavitated_fraction, 0.1);
  EXPECT_EQ(r.fallback_nodes, 0);
  EXPECT_GT(r.flow_ends, 0.0);
  EXPECT_NEAR(supply, r.flow_ends, 1e-6 * r.flow_ends);

  // Squeezing: supply = end leakage + rate of change of the oil volume, sum of theta dh/dt over the film (the
  // model is quasi-static in theta: its own rate is not a state, docs/reynolds.md).
  s.vx = 0.02;
  s.vy = -0.01;
  s.dsy = 3.0;
  const FilmResult q = solve_ok(jfo, s);
  EXPECT_EQ(q.fallback_nodes, 0);
  const std::vector<double> th = jfo.theta_nodes(), z = jfo.z_nodes();
  const double area = g.radius * 2.0 * kPi / g.n_circ * g.length / (g.n_axial + 1);
  double dvdt = 0.0;
  for (int i = 0; i < g.n_circ; ++i)
    for (int j = 0; j < g.n_axial; ++j) {
      const double hdot = -((s.vx + z[j] * s.dsx) * std::cos(th[i]) + (s.vy + z[j] * s.dsy) * std::sin(th[i]));
      dvdt += jfo.film_fraction()[i * g.n_axial + j] * hdot * area;
    }
  supply = 0.0;
  for (const double f : q.hole_flows) supply += f;
  EXPECT_GT(std::abs(dvdt), 0.05 * q.flow_ends);
  EXPECT_NEAR(supply, q.flow_ends + dvdt, 1e-6 * q.flow_ends);
}

TEST(MassConserving, CavitatedZoneCarriesTheCouetteFlux) {
  // JFO/Elrod-Adams: in the cavitated zone the pressure is constant, so the film content is carried by the surfaces
  // alone and theta h (U1 + U2)/2 is conserved along the circumference (steady; upwind faces h at i + 1/2).
  const FilmGeometry g = supplied(2e5);
  FilmSolver jfo(g, kEta, with(Cavitation::MassConserving));
  const FilmState s = journal(0.8, 0.0);
  solve_ok(jfo, s);
  const std::vector<double>& th = jfo.film_fraction();
  const std::vector<double>& p = jfo.pressure();
  const int n = g.n_circ, nz = g.n_axial;
  const std::vector<double> tn = jfo.theta_nodes();
  const double dth = 2.0 * kPi / n;
  int checked = 0;
  auto cav = [&](int i, int j) {
    i = (i + n) % n;
    return j < 0 || j >= nz || (p[i * nz + j] == 0.0 && th[i * nz + j] < 1.0);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < nz; ++j) {
      if (!(cav(i, j) && cav(i - 1, j) && cav(i + 1, j) && cav(i, j - 1) && cav(i, j + 1) && cav(i - 1, j - 1) &&
            cav(i - 1, j + 1)))
        continue;
      const int iw = (i + n - 1) % n;
      const double he = kC - s.ex * std::cos(tn[i] + 0.5 * dth), hw = kC - s.ex * std::cos(tn[iw] + 0.5 * dth);
      EXPECT_NEAR(th[i * nz + j] * he, th[iw * nz + j] * hw, 1e-9 * kC) << i << ", " << j;
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(MassConserving, SqueezeDominatedStatesSolveWithTheFallback) {
  // The model is quasi-static in theta. Where a cavitated gap closes faster than the Couette flow empties it, no
  // steady film fraction exists; those cells fall back to the Swift-Stieber condition (reported), and the active
  // set cannot cycle. Random slow-speed, strong-squeeze states (fixed seed) all solve; in steady rotation none
  // falls back and continuity is exact (ContinuityEndLeakageEqualsSupply).
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int with_fallback = 0;
  for (int trial = 0; trial < 200; ++trial) {
    FilmGeometry g = plain(0.7, 40, 8, 0.005, 15e-6);
    g.holes = {Hole{kPi * (1 + u(rng)), 0.0, 0.002, 1e4 + 2e5 * (1 + u(rng))}};
    FilmSolver jfo(g, 0.0108, with(Cavitation::MassConserving));
    FilmState s = journal(0.95 * std::abs(u(rng)), kPi * u(rng), 100.0 * u(rng), 15e-6);
    s.vx = 0.05 * u(rng);
    s.vy = 0.05 * u(rng);
    FilmResult r;
    ASSERT_TRUE(jfo.solve(s, r)) << trial << ": " << jfo.last_error();
    with_fallback += r.fallback_nodes > 0;
    EXPECT_LE(r.iterations, 40) << trial;
  }
  EXPECT_GT(with_fallback, 0);
}

TEST(MassConserving, NeedsAnOilSupply) {
  FilmSolver jfo(plain(1.0), kEta, with(Cavitation::MassConserving));
  FilmResult r;
  EXPECT_FALSE(jfo.solve(journal(0.5), r));
  EXPECT_THAT(jfo.last_error(), HasSubstr("supply"));
}

TEST(Holes, SupplyHoleAtTheTopFeedsTheEnds) {
  // Centred, non-rotating journal, 2-mm feed hole at 12 o'clock (theta = 90 deg) at 4.5 bar: the nodes in the hole
  // hold the supply pressure, the film around it lies between ambient and supply, the oil fed through the hole
  // leaves through the ends, and the film pushes the journal down.
  FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6);
  g.holes = {Hole{kPi / 2, 0.0, 0.002, 4.5e5}};
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel, Cavitation::MassConserving}) {
    FilmSolver solver(g, 0.0108, with(cav));
    const FilmResult r = solve_ok(solver, FilmState{});
    const std::vector<double>& p = solver.pressure();
    const std::vector<double> th = solver.theta_nodes(), z = solver.z_nodes();
    int in_hole = 0;
    for (int i = 0; i < g.n_circ; ++i)
      for (int j = 0; j < g.n_axial; ++j) {
        const double dx = g.radius * std::remainder(th[i] - kPi / 2, 2 * kPi), dz = z[j];
        const double pk = p[i * g.n_axial + j];
        if (dx * dx + dz * dz <= 1e-6) {
          EXPECT_EQ(pk, 4.5e5);
          ++in_hole;
        } else {
          EXPECT_GT(pk, 0.0);
          EXPECT_LT(pk, 4.5e5);
        }
      }
    EXPECT_GT(in_hole, 4);
    EXPECT_EQ(r.max_pressure, 4.5e5);
    ASSERT_EQ(r.hole_flows.size(), 1u);
    EXPECT_GT(r.hole_flows[0], 0.0);
    EXPECT_NEAR(r.hole_flows[0], r.flow_ends, 1e-9 * r.flow_ends) << to_string(cav);
    EXPECT_LT(r.fy, 0.0);
    EXPECT_NEAR(r.fx, 0.0, 1e-9 * std::abs(r.fy));
    EXPECT_TRUE(r.symmetric);
  }
}

TEST(Holes, OverrideSetsThePressurePerCall) {
  FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6);
  g.holes = {Hole{0.0, 0.0, 0.002, 1e5}, Hole{kPi, 0.0, 0.002, 1e5}};
  FilmSolver solver(g, 0.0108, with(Cavitation::Gumbel));
  FilmState s;
  const FilmResult a = solve_ok(solver, s);
  s.use_override = true;
  s.hole_pressure_override = {3e5, 1e5};
  const FilmResult b = solve_ok(solver, s);
  EXPECT_NEAR(a.fx, 0.0, 1e-9 * std::abs(b.fx));  // equal holes opposite each other: no force
  EXPECT_LT(b.fx, 0.0);  // the stronger hole at theta = 0 pushes the journal towards -x
  EXPECT_EQ(b.max_pressure, 3e5);
  EXPECT_GT(b.hole_flows[0], b.hole_flows[1]);
}

TEST(Solver, FullFilmMatchesSparseLu) {
  // The band L D L^T with its periodic border against Eigen's SparseLU on the same assembled system, on the uniform
  // axial grid and on one graded towards the ends.
  for (const double grading : {0.0, 0.4}) {
    FilmSolver solver(awkward(), 0.0108, with(Cavitation::None, grading));
    const FilmState s = tilted_state();
    const FilmResult r = solve_ok(solver, s);
    EXPECT_FALSE(r.symmetric);
    Eigen::SparseMatrix<double> A;
    Eigen::VectorXd b;
    solver.assemble_full_film_system(s, A, b);
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
    const Eigen::VectorXd x = lu.solve(b);
    const Eigen::Map<const Eigen::VectorXd> p(solver.pressure().data(), x.size());
    EXPECT_LT((p - x).lpNorm<Eigen::Infinity>(), 1e-11 * x.lpNorm<Eigen::Infinity>()) << grading;
  }
}

TEST(Solver, SwiftStieberMatchesProjectedGaussSeidel) {
  // The active-set solution against projected SOR (Cryer 1971) on the assembled system: min p with p >= 0 ...
  FilmSolver solver(awkward(), 0.0108, with(Cavitation::Gumbel));
  const FilmState s = tilted_state();
  const FilmResult r = solve_ok(solver, s);
  EXPECT_GT(r.cavitated_fraction, 0.1);
  Eigen::SparseMatrix<double> Ac;
  Eigen::VectorXd b;
  solver.assemble_full_film_system(s, Ac, b);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = Ac;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  for (int sweep = 0; sweep < 20000; ++sweep) {
    double change = 0.0;
    for (int k = 0; k < A.rows(); ++k) {
      double diag = 0.0, off = 0.0;
      int nnz = 0;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, k); it; ++it, ++nnz) {
        if (it.col() == k)
          diag = it.value();
        else
          off += it.value() * x[it.col()];
      }
      double v = (b[k] - off) / diag;
      if (nnz > 1) v = std::max(0.0, x[k] + 1.8 * (v - x[k]));  // hole and groove rows are identities
      change = std::max(change, std::abs(v - x[k]));
      x[k] = v;
    }
    if (change < 1e-13 * x.lpNorm<Eigen::Infinity>()) break;
  }
  const Eigen::Map<const Eigen::VectorXd> p(solver.pressure().data(), x.size());
  EXPECT_LT((p - x).lpNorm<Eigen::Infinity>(), 1e-9 * x.lpNorm<Eigen::Infinity>());
}

TEST(Solver, MidWidthSymmetryMatchesTheFullGrid) {
  // Solving half the film (even and odd axial counts, uniform and graded axial grids) gives the full grid's answer.
  for (const double grading : {0.0, 0.4}) {
    for (const int nz : {12, 13})
      for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel, Cavitation::MassConserving}) {
        FilmGeometry g = plain(0.7, 60, nz, 0.005, 15e-6);
        g.holes = {Hole{kPi / 2, 0.0, 0.002, 4.5e5}, Hole{kPi, 0.002, 0.001, 1e5}, Hole{kPi, -0.002, 0.001, 1e5}};
        const SolverOptions o = with(cav, grading);
        SolverOptions full = o;
        full.use_symmetry = false;
        FilmSolver half_solver(g, 0.0108, o), full_solver(g, 0.0108, full);
        FilmState s = journal(0.7, 0.4, 10000.0, 15e-6);
        s.vx = 0.01;
        const FilmResult a = solve_ok(half_solver, s), b = solve_ok(full_solver, s);
        EXPECT_TRUE(a.symmetric);
        EXPECT_FALSE(b.symmetric);
        const double F = std::hypot(b.fx, b.fy);
        EXPECT_NEAR(a.fx, b.fx, 1e-9 * F) << nz << " " << to_string(cav) << " " << grading;
        EXPECT_NEAR(a.fy, b.fy, 1e-9 * F) << nz << " " << to_string(cav);
        EXPECT_NEAR(a.torque_inner, b.torque_inner, 1e-9 * std::abs(b.torque_inner));
        EXPECT_NEAR(a.flow_ends, b.flow_ends, 1e-9 * std::abs(b.flow_ends));
        for (int h = 0; h < 3; ++h) EXPECT_NEAR(a.hole_flows[h], b.hole_flows[h], 1e-9 * std::abs(b.flow_ends));
        EXPECT_EQ(a.cavitated_fraction, b.cavitated_fraction);
      }
  }
}

TEST(BadInput, ConstructorRejectsWithAClearMessage) {
  auto message = [](FilmGeometry g, double eta = kEta, SolverOptions o = {}) -> std::string {
    try {
      FilmSolver s(g, eta, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  FilmGeometry g = plain(1.0);
  g.clearance = 0.0;
  EXPECT_THAT(message(g), HasSubstr("clearance"));
  g = plain(1.0);
  g.n_circ = 6;
  EXPECT_THAT(message(g), HasSubstr("8 x 4"));
  g = plain(1.0);
  g.n_axial = 3;
  EXPECT_THAT(message(g), HasSubstr("8 x 4"));
  g = plain(1.0);
  g.holes = {Hole{0.0, 0.024, 0.004, 1e5}};  // reaches beyond z = L/2 = 25 mm
  EXPECT_THAT(message(g), HasSubstr("not inside the film"));
  g = plain(1.0);
  g.holes = {Hole{0.0, 0.0, 0.004, 1e5}, Hole{0.05, 0.0, 0.004, 1e5}};
  EXPECT_THAT(message(g), HasSubstr("overlaps"));
  g = plain(1.0);
  g.holes.assign(9, Hole{0.0, 0.0, 0.001, 0.0});
  EXPECT_THAT(message(g), HasSubstr("at most 8"));
  g = plain(1.0);
  g.grooves = {Groove{0.02, 0.02, 1e5}};
  EXPECT_THAT(message(g), HasSubstr("not inside the film"));
  EXPECT_THAT(message(plain(1.0), 0.0), HasSubstr("viscosity"));
  SolverOptions o;
  o.tolerance = 0.0;
  EXPECT_THAT(message(plain(1.0), kEta, o), HasSubstr("tolerance"));
}

TEST(FilmGeometry, ThinnestFilmIsTheClearanceLessTheLargestOffsetOverTheWidth) {
  // h = c - |e + z s| over z in [-L/2, L/2]; |e + z s| is convex in z, so its largest value is at an end.
  const FilmGeometry g = plain(1.0);  // L = 2R
  const double hl = kR;
  EXPECT_NEAR(min_film_thickness(g, journal(0.0)), kC, 1e-18);
  EXPECT_NEAR(min_film_thickness(g, journal(0.6, 1.1)), 0.4 * kC, 1e-18);  // untilted: c (1 - eps)
  // Offset along x, tilt along y: both ends sqrt(e^2 + (L/2 s)^2) off the axis.
  FilmState s = journal(0.6);
  s.sy = 0.3 * kC / hl;
  EXPECT_NEAR(min_film_thickness(g, s), kC - std::hypot(0.6 * kC, 0.3 * kC), 1e-18);
  // Tilt in the offset's plane: one end 0.9 c off, the other 0.3 c.
  s.sy = 0.0;
  s.sx = 0.3 * kC / hl;
  EXPECT_NEAR(min_film_thickness(g, s), 0.1 * kC, 1e-18);
  s.sx = -s.sx;
  EXPECT_NEAR(min_film_thickness(g, s), 0.1 * kC, 1e-18);
  // The solver refuses exactly the states whose thinnest film is not positive.
  FilmSolver solver(g, kEta);
  FilmResult r;
  s.sx = 0.39 * kC / hl;  // 0.01 c left at one end
  EXPECT_GT(min_film_thickness(g, s), 0.0);
  EXPECT_TRUE(solver.solve(s, r)) << solver.last_error();
  s.sx = 0.41 * kC / hl;
  EXPECT_LT(min_film_thickness(g, s), 0.0);
  EXPECT_FALSE(solver.solve(s, r));
  EXPECT_THAT(solver.last_error(), HasSubstr("film closes"));
}

TEST(BadInput, ClosingFilmReturnsFalse) {
  FilmSolver solver(plain(1.0), kEta);
  FilmResult r;
  r.fx = 123.0;
  EXPECT_FALSE(solver.solve(journal(1.0), r));
  EXPECT_THAT(solver.last_error(), HasSubstr("film closes"));
  EXPECT_EQ(r.fx, 123.0);  // left unchanged
  EXPECT_FALSE(solver.solve(journal(1.3), r));
  // Centred but tilted so far that the ends touch.
  FilmState s = journal(0.0);
  s.sx = 1.01 * kC / (0.5 * 2.0 * kR);
  EXPECT_FALSE(solver.solve(s, r));
  EXPECT_THAT(solver.last_error(), HasSubstr("film closes"));
  s = journal(0.5);
  s.vx = std::nan("");
  EXPECT_FALSE(solver.solve(s, r));
  EXPECT_THAT(solver.last_error(), HasSubstr("not finite"));
  // ... and the solver works again afterwards.
  EXPECT_TRUE(solver.solve(journal(0.5), r)) << solver.last_error();
}

TEST(WarmStart, RepeatedSolvesAreIdenticalAndHistoryDoesNotMatter) {
  for (const Cavitation cav : {Cavitation::Gumbel, Cavitation::MassConserving}) {
    FilmGeometry g = plain(0.7, 60, 12, 0.005, 15e-6);
    for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2, 0.0, 0.002, 2e5});
    FilmState a = journal(0.6, 0.3, 10000.0, 15e-6), b = journal(0.8, 2.5, 10000.0, 15e-6);
    a.sx = 3e-4;
    b.vy = 0.02;
    FilmSolver cold(g, 0.0108, with(cav)), warm(g, 0.0108, with(cav));
    const FilmResult ref = solve_ok(cold, a);
    const FilmResult again = solve_ok(cold, a);
    EXPECT_EQ(again.fx, ref.fx) << to_string(cav);
    EXPECT_EQ(again.fy, ref.fy);
    EXPECT_EQ(again.my, ref.my);
    EXPECT_EQ(again.iterations, 1);  // the warm active set is already right
    solve_ok(warm, b);
    const FilmResult r = solve_ok(warm, a);
    const double F = std::hypot(ref.fx, ref.fy);
    EXPECT_NEAR(r.fx, ref.fx, 1e-9 * F) << to_string(cav);
    EXPECT_NEAR(r.fy, ref.fy, 1e-9 * F) << to_string(cav);
    EXPECT_NEAR(r.flow_ends, ref.flow_ends, 1e-9 * ref.flow_ends) << to_string(cav);
  }
}

// Warm and cold starts of the Swift-Stieber problem reach the same cavitated set (the complementarity solution is
// unique for the M-matrix of the film), so along a whirl orbit the warm-started forces equal cold solves to
// round-off, not only to the 1e-9 of the mixed-history check above, while taking fewer sweeps when the state moves
// as little as between integrator steps (0.25 degrees of whirl per call, as in bench/reynolds_benchmark.cpp).
TEST(WarmStart, SwiftStieberForcesAlongAWhirlEqualColdSolvesToRoundOff) {
  FilmGeometry g = plain(0.7, 48, 10, 0.005, 15e-6);
  for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2, 0.0, 0.002, 2e5});
  FilmSolver warm(g, 0.0108, with(Cavitation::Gumbel));
  int warm_sweeps = 0, cold_sweeps = 0;
  for (int step = 0; step < 60; ++step) {
    const double phi = step * kPi / 720.0;
    FilmState s = journal(0.7, phi, 10000.0, 15e-6);
    s.sx = 4e-4 * std::cos(phi);
    s.sy = 4e-4 * std::sin(phi);
    s.vx = -0.02 * std::sin(phi);
    s.vy = 0.02 * std::cos(phi);
    FilmSolver cold(g, 0.0108, with(Cavitation::Gumbel));
    const FilmResult c = solve_ok(cold, s);
    const FilmResult w = solve_ok(warm, s);
    const double F = std::hypot(c.fx, c.fy), M = std::hypot(c.mx, c.my);
    constexpr double kRoundOff = 1e-12;  // a direct band solve of ~480 unknowns on the same set
    EXPECT_NEAR(w.fx, c.fx, kRoundOff * F) << step;
    EXPECT_NEAR(w.fy, c.fy, kRoundOff * F) << step;
    EXPECT_NEAR(w.mx, c.mx, kRoundOff * M) << step;
    EXPECT_NEAR(w.my, c.my, kRoundOff * M) << step;
    EXPECT_NEAR(w.torque_inner, c.torque_inner, kRoundOff * std::abs(c.torque_inner)) << step;
    EXPECT_EQ(w.cavitated_fraction, c.cavitated_fraction) << step;
    if (step > 0) warm_sweeps += w.iterations, cold_sweeps += c.iterations;
  }
  EXPECT_LT(warm_sweeps, cold_sweeps / 2);
}

// A floating ring's inner film as the reuse tests see it: four drill holes at mid-width, the journal eccentric,
// tilted, squeezing and spinning against a spinning ring.
FilmGeometry holed_film() {
  FilmGeometry g = plain(0.7, 48, 10, 0.005, 15e-6);
  for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2 + 0.3, 0.0, 0.002, 2e5});
  return g;
}
// One input of a FilmState to perturb in the reuse tests: its name, how to change it by t, and a typical change.
struct Direction {
  const char* name;
  void (*apply)(FilmState&, double);
  double scale;
};

FilmState tilted_squeezing_journal() {
  FilmState a = journal(0.6, 0.3, 10000.0, 15e-6);
  a.sx = 3e-4;
  a.sy = -1e-4;
  a.vx = 0.01;
  a.vy = -0.005;
  a.dsx = 0.5;
  a.dsy = 0.2;
  a.omega_outer = 2000.0;
  return a;
}

// solve_same_matrix reuses the last solve's factorisation and cavitated set for new velocities, speeds and hole
// pressures. For a fixed set the film is affine in them, so: at the solved state it reproduces the solve; it is
// affine in each of these inputs; for a change too small to move the set it equals a new solve; and it refuses a
// changed thickness, a change of the mid-width symmetry and the mass-conserving model.
TEST(SameMatrix, ReusesTheFactorisationForVelocitiesSpeedsAndHolePressures) {
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    const FilmGeometry g = holed_film();
    FilmState a = tilted_squeezing_journal();
    a.use_override = true;
    for (int k = 0; k < 4; ++k) a.hole_pressure_override[k] = 2e5 + 1e4 * k;
    FilmSolver solver(g, 0.0108, with(cav));
    const FilmResult base = solve_ok(solver, a);
    const double F = std::hypot(base.fx, base.fy), M = std::hypot(base.mx, base.my);
    const double T = std::abs(base.torque_inner);
    FilmResult r;
    ASSERT_TRUE(solver.solve_same_matrix(a, r)) << solver.last_error();
    EXPECT_NEAR(r.fx, base.fx, 1e-13 * F) << to_string(cav);
    EXPECT_NEAR(r.my, base.my, 1e-13 * M) << to_string(cav);
    EXPECT_EQ(r.linear_solves, 1);
    EXPECT_EQ(r.iterations, 0);
    // Directions: squeeze velocities, tilt rates, journal speed, one hole's pressure (scale: a typical change).
    const Direction dirs[] = {{"vx", [](FilmState& s, double t) { s.vx += t; }, 0.01},
                              {"vy", [](FilmState& s, double t) { s.vy += t; }, 0.01},
                              {"dsx", [](FilmState& s, double t) { s.dsx += t; }, 0.5},
                              {"dsy", [](FilmState& s, double t) { s.dsy += t; }, 0.5},
                              {"omega", [](FilmState& s, double t) { s.omega_inner += t; }, 1000.0},
                              {"hole", [](FilmState& s, double t) { s.hole_pressure_override[1] += t; }, 1e4}};
    for (const Direction& dir : dirs) {
      auto same = [&](double t) {
        FilmState s = a;
        dir.apply(s, t * dir.scale);
        FilmResult out;
        EXPECT_TRUE(solver.solve_same_matrix(s, out)) << solver.last_error();
        return out;
      };
      const FilmResult r1 = same(0.1), r2 = same(0.2);
      // Affine: the change for twice the step is twice the change (to round-off relative to the film's loads).
      const double d1 = std::hypot(r1.fx - base.fx, r1.fy - base.fy);
      EXPECT_GT(d1, 1e-6 * F) << dir.name << " moves the film";
      EXPECT_NEAR(r2.fx - base.fx, 2.0 * (r1.fx - base.fx), 1e-11 * F) << dir.name << " " << to_string(cav);
      EXPECT_NEAR(r2.fy - base.fy, 2.0 * (r1.fy - base.fy), 1e-11 * F) << dir.name;
      EXPECT_NEAR(r2.mx - base.mx, 2.0 * (r1.mx - base.mx), 1e-11 * M) << dir.name;
      EXPECT_NEAR(r2.torque_inner - base.torque_inner, 2.0 * (r1.torque_inner - base.torque_inner), 1e-11 * T)
          << dir.name;
      // A change too small to move the cavitated set: a new (warm) solve takes one sweep and gives the same film.
      const FilmResult small = same(1e-6);
      FilmState s = a;
      dir.apply(s, 1e-6 * dir.scale);
      FilmSolver fresh(g, 0.0108, with(cav));
      solve_ok(fresh, a);
      const FilmResult full = solve_ok(fresh, s);
      EXPECT_EQ(full.iterations, 1) << dir.name;
      EXPECT_NEAR(small.fx, full.fx, 1e-12 * F) << dir.name << " " << to_string(cav);
      EXPECT_NEAR(small.fy, full.fy, 1e-12 * F) << dir.name;
      EXPECT_NEAR(small.my, full.my, 1e-12 * M) << dir.name;
      EXPECT_NEAR(small.torque_outer, full.torque_outer, 1e-12 * T) << dir.name;
      EXPECT_NEAR(small.flow_ends, full.flow_ends, 1e-11 * std::abs(full.flow_ends)) << dir.name;
    }
    // Refusals: another thickness; a state that would be solved on the symmetric half; nothing solved yet.
    FilmState moved = a;
    moved.ex += 1e-9;
    EXPECT_FALSE(solver.solve_same_matrix(moved, r));
    EXPECT_THAT(solver.last_error(), HasSubstr("thickness"));
    FilmState flat = journal(0.6, 0.3, 10000.0, 15e-6);
    solve_ok(solver, flat);  // no tilt, symmetric holes: the half-grid solve
    flat.dsx = 0.1;
    EXPECT_FALSE(solver.solve_same_matrix(flat, r));
    EXPECT_THAT(solver.last_error(), HasSubstr("symmetry"));
    FilmSolver unsolved(g, 0.0108, with(cav));
    EXPECT_FALSE(unsolved.solve_same_matrix(a, r));
  }
  FilmSolver jfo(supplied(2e5), kEta, with(Cavitation::MassConserving));
  FilmResult r;
  solve_ok(jfo, journal(0.6));
  EXPECT_FALSE(jfo.solve_same_matrix(journal(0.6), r));
  EXPECT_THAT(jfo.last_error(), HasSubstr("mass-conserving"));
}

// solve_same_matrix computes only the sources anew when the solver's thickness arrays are the factorisation's,
// and everything when a linearised solve for another thickness has overwritten them: after solve_linearised the
// film is bit for bit that of a solver that went straight from the solve to solve_same_matrix.
TEST(SameMatrix, AfterALinearisedSolveItUsesTheFactorisationsThickness) {
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    const FilmGeometry g = holed_film();
    const FilmState a = tilted_squeezing_journal();
    FilmState moved = a, faster = a;
    moved.ex += 2e-7;
    moved.sy -= 1e-5;
    faster.vx += 0.003;
    faster.omega_inner *= 1.01;
    FilmSolver direct(g, 0.0108, with(cav)), detour(g, 0.0108, with(cav));
    solve_ok(direct, a);
    solve_ok(detour, a);
    FilmResult lin, want, got;
    ASSERT_TRUE(detour.solve_linearised(moved, lin)) << detour.last_error();
    ASSERT_TRUE(direct.solve_same_matrix(faster, want)) << direct.last_error();
    ASSERT_TRUE(detour.solve_same_matrix(faster, got)) << detour.last_error();
    EXPECT_NE(lin.fx, want.fx);
    EXPECT_EQ(got.fx, want.fx) << to_string(cav);
    EXPECT_EQ(got.fy, want.fy) << to_string(cav);
    EXPECT_EQ(got.my, want.my) << to_string(cav);
    EXPECT_EQ(got.torque_inner, want.torque_inner) << to_string(cav);
    // And again from the same matrix (now the light path on both).
    ASSERT_TRUE(detour.solve_same_matrix(a, got));
    ASSERT_TRUE(direct.solve_same_matrix(a, want));
    EXPECT_EQ(got.fx, want.fx);
    EXPECT_EQ(got.flow_ends, want.flow_ends);
  }
}

// solve_linearised: one Newton step from the last solve's pressure with its factorisation and cavitated set. At
// the solved state it reproduces the solve; velocities alone make it solve_same_matrix; for a thickness change too
// small to move the set its difference from a new solve is second order in the change (halving the change divides
// it by 4), and far below the change of the film itself.
TEST(Linearised, OneNewtonStepIsSecondOrderInTheThicknessChange) {
  for (const Cavitation cav : {Cavitation::None, Cavitation::Gumbel}) {
    const FilmGeometry g = holed_film();
    const FilmState a = tilted_squeezing_journal();
    FilmSolver solver(g, 0.0108, with(cav));
    const FilmResult base = solve_ok(solver, a);
    const double F = std::hypot(base.fx, base.fy), M = std::hypot(base.mx, base.my);
    FilmResult r;
    ASSERT_TRUE(solver.solve_linearised(a, r)) << solver.last_error();
    EXPECT_NEAR(r.fx, base.fx, 1e-12 * F) << to_string(cav);
    EXPECT_NEAR(r.my, base.my, 1e-12 * M) << to_string(cav);
    EXPECT_EQ(r.linear_solves, 1);
    EXPECT_EQ(r.iterations, 0);
    FilmState faster = a;
    faster.vx += 0.003;
    FilmResult same, lin;
    ASSERT_TRUE(solver.solve_same_matrix(faster, same));
    ASSERT_TRUE(solver.solve_linearised(faster, lin));
    EXPECT_NEAR(lin.fx, same.fx, 1e-12 * F);
    EXPECT_NEAR(lin.fy, same.fy, 1e-12 * F);
    const Direction dirs[] = {{"ex", [](FilmState& s, double t) { s.ex += t; }, 1e-9},
                              {"ey", [](FilmState& s, double t) { s.ey += t; }, 1e-9},
                              {"sx", [](FilmState& s, double t) { s.sx += t; }, 2e-7},
                              {"sy", [](FilmState& s, double t) { s.sy += t; }, 2e-7}};
    for (const Direction& dir : dirs) {
      double err[2], change[2];
      for (int h = 0; h < 2; ++h) {
        FilmState s = a;
        dir.apply(s, dir.scale / (1 << h));
        FilmResult l;
        ASSERT_TRUE(solver.solve_linearised(s, l)) << solver.last_error();
        FilmSolver fresh(g, 0.0108, with(cav));
        solve_ok(fresh, a);
        const FilmResult full = solve_ok(fresh, s);
        ASSERT_EQ(full.iterations, 1) << dir.name << ": the set moved, choose a smaller change";
        // Loads in units of the base film's: force, moment and torque alike.
        const double T = std::abs(base.torque_inner);
        auto diff = [&](const FilmResult& x, const FilmResult& y) {
          return std::sqrt(std::pow((x.fx - y.fx) / F, 2) + std::pow((x.fy - y.fy) / F, 2) +
                           std::pow((x.mx - y.mx) / M, 2) + std::pow((x.my - y.my) / M, 2) +
                           std::pow((x.torque_inner - y.torque_inner) / T, 2));
        };
        err[h] = diff(l, full);
        change[h] = diff(full, base);
      }
      EXPECT_LT(err[0], 1e-2 * change[0]) << dir.name << " " << to_string(cav);
      EXPECT_GT(err[0] / err[1], 3.0) << dir.name << " " << to_string(cav) << ": second order";
      EXPECT_LT(err[0] / err[1], 5.0) << dir.name << " " << to_string(cav);
    }
    // Refusals: the film closes; a state that would be solved on the symmetric half; nothing solved yet.
    FilmState closed = a;
    closed.ex = 15e-6;
    EXPECT_FALSE(solver.solve_linearised(closed, r));
    EXPECT_THAT(solver.last_error(), HasSubstr("closes"));
    solve_ok(solver, journal(0.6, 0.3, 10000.0, 15e-6));  // no tilt, symmetric holes: the half-grid solve
    EXPECT_FALSE(solver.solve_linearised(a, r));
    EXPECT_THAT(solver.last_error(), HasSubstr("symmetry"));
    FilmSolver unsolved(g, 0.0108, with(cav));
    EXPECT_FALSE(unsolved.solve_linearised(a, r));
  }
  FilmSolver jfo(supplied(2e5), kEta, with(Cavitation::MassConserving));
  FilmResult r;
  solve_ok(jfo, journal(0.6));
  EXPECT_FALSE(jfo.solve_linearised(journal(0.6), r));
  EXPECT_THAT(jfo.last_error(), HasSubstr("mass-conserving"));
}

}  // namespace
TEST(ForcesOnly, LoadsAreThoseOfAFullSolveAndTheRestIsNaN) {
  // set_forces_only(true) (the squeeze-film dampers): the same forces (to round-off where the film is symmetric
  // about mid-width, whose forces are then summed over the reduced rows), moments, peak pressure, cavitated share,
  // counters and pressure field bit for bit, torques and flows NaN; the warm start is a full solve's, so a sequence
  // of states gives the same loads with and without it, by solve(), solve_same_matrix() and solve_linearised(). A
  // tilted, spinning film with a hole (no mid-width symmetry) and a squeeze film of a damper (symmetric; even and odd
  // axial node counts), both models of the active set that have a factorisation to reuse.
  FilmGeometry tilted = plain(0.7, 48, 10, 0.005, 15e-6);
  tilted.holes = {Hole{kPi / 2, 0.0, 0.002, 2e5}};
  FilmGeometry damper = plain(0.3, 48, 8, 0.01025, 51e-6);
  damper.holes = {Hole{kPi / 2, 0.0, 0.002, 4e5}};
  FilmGeometry damper_odd = damper;  // a mid-width row of its own
  damper_odd.n_axial = 7;
  for (const FilmGeometry* g : {&tilted, &damper, &damper_odd}) {
    FilmSolver full(*g, 0.0108, with(Cavitation::Gumbel)), lean(*g, 0.0108, with(Cavitation::Gumbel));
    lean.set_forces_only(true);
    const double c = g->clearance;
    for (int step = 0; step < 6; ++step) {
      // Every third step a new position and solve(); then the same position with new velocities (same matrix);
      // then that position moved by 1e-3 c (linearised).
      const int kind = step % 3, base = step - kind;
      FilmState s;
      s.ex = c * (0.3 + 0.1 * base) * std::cos(0.4 * base) + (kind == 2 ? 1e-3 * c : 0.0);
      s.ey = c * (0.3 + 0.1 * base) * std::sin(0.4 * base);
      s.vx = -0.02 * step;
      s.vy = 0.01;
      if (g == &tilted) {
        s.sy = 0.2 * c / g->length;
        s.omega_inner = 10000.0;
      }
      FilmResult rf, rl;
      if (kind == 1) {
        ASSERT_TRUE(full.solve_same_matrix(s, rf));
        ASSERT_TRUE(lean.solve_same_matrix(s, rl));
      } else if (kind == 2) {
        ASSERT_TRUE(full.solve_linearised(s, rf));
        ASSERT_TRUE(lean.solve_linearised(s, rl));
      } else {
        rf = solve_ok(full, s);
        rl = solve_ok(lean, s);
      }
      if (rf.symmetric) {
        // Summed over the reduced rows (half the work): the same forces to round-off.
        const double scale = std::hypot(rf.fx, rf.fy);
        EXPECT_GT(scale, 1.0);
        EXPECT_NEAR(rl.fx, rf.fx, 1e-13 * scale) << "step " << step;
        EXPECT_NEAR(rl.fy, rf.fy, 1e-13 * scale) << "step " << step;
      } else {
        EXPECT_EQ(rl.fx, rf.fx) << "step " << step;
        EXPECT_EQ(rl.fy, rf.fy) << "step " << step;
      }
      EXPECT_EQ(rl.mx, rf.mx) << "step " << step;
      EXPECT_EQ(rl.my, rf.my) << "step " << step;
      EXPECT_EQ(rl.max_pressure, rf.max_pressure);
      EXPECT_EQ(rl.cavitated_fraction, rf.cavitated_fraction);
      EXPECT_EQ(rl.iterations, rf.iterations);
      EXPECT_EQ(rl.symmetric, rf.symmetric);
      EXPECT_TRUE(std::isfinite(rf.torque_inner) && std::isfinite(rf.flow_ends));
      EXPECT_TRUE(std::isnan(rl.torque_inner) && std::isnan(rl.torque_outer) && std::isnan(rl.flow_ends));
      ASSERT_EQ(rl.hole_flows.size(), 1u);
      EXPECT_TRUE(std::isnan(rl.hole_flows[0]));
      // The fields, expanded to the full grid when asked for (every other step here, so that the warm start is
      // taken both from the expanded and from the solver's own fields).
      if (step % 2 == 1) {
        EXPECT_EQ(lean.pressure(), full.pressure()) << "step " << step;
        EXPECT_EQ(lean.film_fraction(), full.film_fraction()) << "step " << step;
        EXPECT_EQ(lean.node_pressure(5, 2), full.pressure()[5 * g->n_axial + 2]);
      } else {
        EXPECT_EQ(lean.node_pressure(7, g->n_axial - 1), full.node_pressure(7, g->n_axial - 1)) << "step " << step;
      }
    }
    // Switched off again, the next solve gives a full solve's outputs and fields (from the same warm start).
    lean.set_forces_only(false);
    FilmState s;
    s.ex = 0.5 * c;
    s.vy = 0.02;
    const FilmResult rf = solve_ok(full, s), rl = solve_ok(lean, s);
    EXPECT_EQ(rl.fx, rf.fx);
    EXPECT_EQ(rl.torque_inner, rf.torque_inner);
    EXPECT_EQ(lean.pressure(), full.pressure());
    EXPECT_EQ(lean.film_fraction(), full.film_fraction());
  }
}

}  // namespace turbodyn::reynolds
