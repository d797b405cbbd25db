// Film geometries and states shared by the Reynolds solver tests (tests/model/films/reynolds*_test.cpp).
#pragma once

#include <cmath>

#include <gtest/gtest.h>

#include "model/films/reynolds.h"
#include "model/spec/constants.h"

namespace turbodyn::reynolds::testing {


// The Raimondi-Boyd example bearing: D = 50 mm, c = 50 um, 20 mPa s, 30 rev/s (any consistent set gives the same
// dimensionless numbers).
inline constexpr double kR = 0.025, kC = 50e-6, kEta = 0.02, kRevs = 30.0, kOmega = 2.0 * kPi * kRevs;

inline FilmGeometry plain(double l_over_d, int n_circ = 60, int n_axial = 12, double R = kR, double c = kC) {
  FilmGeometry g;
  g.radius = R;
  g.length = l_over_d * 2.0 * R;
  g.clearance = c;
  g.n_circ = n_circ;
  g.n_axial = n_axial;
  return g;
}

inline SolverOptions with(Cavitation cav, double axial_grading = 0.0) {
  SolverOptions o;
  o.cavitation = cav;
  o.axial_grading = axial_grading;
  return o;
}

inline FilmState journal(double eps, double angle = 0.0, double omega = kOmega, double c = kC) {
  FilmState s;
  s.ex = eps * c * std::cos(angle);
  s.ey = eps * c * std::sin(angle);
  s.omega_inner = omega;
  return s;
}

inline FilmResult solve_ok(FilmSolver& solver, const FilmState& s) {
  FilmResult r;
  EXPECT_TRUE(solver.solve(s, r)) << solver.last_error();
  return r;
}

// Components of the film force on the journal in the closed forms' convention: F = -radial e_r + tangential e_t,
// e_r along the eccentricity at `angle`, e_t = e_z x e_r.
inline Closed components(const FilmResult& r, double angle = 0.0) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  return {-(r.fx * ca + r.fy * sa), -r.fx * sa + r.fy * ca};
}

inline double rel(double a, double b) { return std::abs(a / b - 1.0); }

inline FilmGeometry supplied(double pressure, double diameter = 0.01, double theta = kPi) {
  FilmGeometry g = plain(1.0, 60, 12);
  g.holes = {Hole{theta, 0.0, diameter, pressure}};
  return g;
}

inline FilmGeometry awkward() {  // tilt-free mid-width asymmetry, holes of different sizes, a groove: the general case
  FilmGeometry g = plain(0.7, 48, 10, 0.005, 15e-6);
  g.holes = {Hole{0.3, 0.0005, 0.002, 2e5}, Hole{2.0, -0.001, 0.0015, 1e5}, Hole{4.0, 0.0, 0.0005, 0.5e5}};
  g.grooves = {Groove{0.0025, 0.0006, 0.3e5}};  // its outer land holds a row
  return g;
}

inline FilmState tilted_state() {
  FilmState s;
  s.ex = 5e-6;
  s.ey = -3e-6;
  s.sx = 1e-3;
  s.sy = -1.5e-3;
  s.vx = 2e-3;
  s.vy = -1e-3;
  s.dsx = 0.2;
  s.dsy = 0.1;
  s.omega_inner = 8000;
  s.omega_outer = 1500;
  return s;
}

}  // namespace turbodyn::reynolds::testing
