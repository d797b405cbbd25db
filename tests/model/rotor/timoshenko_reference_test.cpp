// Shaft finite elements against closed-form beam theory: shear factors, the element stiffness, whole-beam
// frequencies (Euler-Bernoulli, Timoshenko, exact transfer matrix) and the convergence order under refinement.
#include "model/rotor/timoshenko.h"

#include <cmath>

#include <gtest/gtest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "model/rotor/rotor.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::planar_frequencies;
using testing::uniform_beam;

using testing::kE;
using testing::kG;
using testing::kNu;
using testing::kRho;
using testing::solid;

// ---------------------------------------------------------------------------------- whole beams, closed forms

constexpr double kLength = 1.0, kDiameter = 0.05;

double eb_pinned(int n) {  // Euler-Bernoulli simply supported: (n pi / L)^2 sqrt(EI / rho A)
  const double A = M_PI * kDiameter * kDiameter / 4, I = M_PI * std::pow(kDiameter, 4) / 64;
  return std::pow(n * M_PI / kLength, 2) * std::sqrt(kE * I / (kRho * A));
}

double eb_free(int n) {  // Euler-Bernoulli free-free: (beta_n L)^2 / L^2 sqrt(EI / rho A)
  const double betaL[] = {4.730040744862704, 7.853204624095838, 10.995607838001671};
  const double A = M_PI * kDiameter * kDiameter / 4, I = M_PI * std::pow(kDiameter, 4) / 64;
  return std::pow(betaL[n - 1] / kLength, 2) * std::sqrt(kE * I / (kRho * A));
}

// Timoshenko simply supported (Timoshenko 1921; e.g. Han, Benaroya & Wei 1999, J. Sound Vib. 225): the lower root of
// (rho^2 I / kGA') w^4 - (rho A + rho I k^2 (1 + E / (kappa G))) w^2 + EI k^4 = 0, k = n pi / L, per unit area terms.
double timoshenko_pinned(int n, double L, double d, double kappa) {
  const double A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64, k = n * M_PI / L;
  const double a = kRho * kRho * I / (kappa * kG);
  const double b = kRho * A + kRho * I * k * k * (1 + kE / (kappa * kG));
  const double c = kE * I * std::pow(k, 4);
  return std::sqrt((b - std::sqrt(b * b - 4 * a * c)) / (2 * a));
}

// Exact Timoshenko free-free frequencies from the transfer matrix of the governing ODEs
//   kGA (w'' - phi') + rho A w^2 w = 0,  EI phi'' + kGA (w' - phi) + rho I w^2 phi = 0,
// with zero shear force and moment at both ends; roots of the 2x2 boundary determinant by bisection.
double timoshenko_free_determinant(double w, double L, double d, double kappa) {
  const double A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64, kGA = kappa * kG * A, EI = kE * I;
  Eigen::Matrix4d S = Eigen::Matrix4d::Zero();  // y = [w, w', phi, phi']
  S(0, 1) = 1;
  S(1, 0) = -kRho * A * w * w / kGA;
  S(1, 3) = 1;
  S(2, 3) = 1;
  S(3, 1) = -kGA / EI;
  S(3, 2) = (kGA - kRho * I * w * w) / EI;
  const Eigen::Matrix4d T = (S * L).exp();
  const Eigen::Vector4d a = T.col(0), b = T.col(1) + T.col(2);  // y0 = [1,0,0,0] and [0,1,1,0]
  return (a(1) - a(2)) * b(3) - (b(1) - b(2)) * a(3);
}

std::vector<double> timoshenko_free(int count, double L, double d, double kappa, double w_start, double w_step) {
  std::vector<double> roots;
  double w0 = w_start, f0 = timoshenko_free_determinant(w0, L, d, kappa);
  while (static_cast<int>(roots.size()) < count) {
    const double w1 = w0 + w_step, f1 = timoshenko_free_determinant(w1, L, d, kappa);
    if (f0 * f1 < 0) {
      double lo = w0, hi = w1, flo = f0;
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi), fm = timoshenko_free_determinant(mid, L, d, kappa);
        if ((fm < 0) == (flo < 0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      roots.push_back(0.5 * (lo + hi));
    }
    w0 = w1;
    f0 = f1;
  }
  return roots;
}

// Discretisation error allowed for the first three modes on the meshes below (20 Euler-Bernoulli elements, 80
// Timoshenko elements on a beam with L/d = 5); the rates are checked separately.
constexpr double kMeshTolerance = 1e-4;

std::vector<int> end_nodes(const Rotor& r) { return {0, static_cast<int>(r.node_z.size()) - 1}; }

// Convergence under mesh refinement, observed order log2(e(h) / e(h/2)) of the second frequency.
// - Euler-Bernoulli (Hermite cubics, consistent mass): order 4 (Strang & Fix 1973, "An Analysis of the Finite
//   Element Method", eigenvalue error h^(2(k+1-m)) with k = 3, m = 2).
// - Timoshenko interdependent-interpolation element: its shape functions depend on Phi = 12EI/(kappa G A h^2),
//   which grows as h shrinks; for h well below the shaft diameter they tend to linear w and phi, and the
//   consistent-mass frequency error falls as h^2 (measured ratio 4.00 per halving, see docs/validation.md).
double observed_order(bool shear, int mode, bool pinned, int coarse) {
  const double L = 0.25, d = 0.05, kappa = cowper_shear_factor(kNu, 0.0);
  double exact;
  if (shear) {
    exact = pinned ? timoshenko_pinned(mode, L, d, kappa) : timoshenko_free(mode, L, d, kappa, 100.0, 50.0)[mode - 1];
  } else {
    const double A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64;
    exact = std::pow(mode * M_PI / L, 2) * std::sqrt(kE * I / (kRho * A));
  }
  std::vector<double> err;
  for (int n : {coarse, 2 * coarse}) {
    const Rotor r = build_rotor(uniform_beam(L, d, n, shear, shear));
    const std::vector<double> w = planar_frequencies(r, pinned ? end_nodes(r) : std::vector<int>{}, 10.0);
    err.push_back(std::abs(w[mode - 1] - exact) / exact);
  }
  return std::log2(err[0] / err[1]);
}

TEST(ShearFactor, PublishedFormulas) {
  // Cowper (1966) solid circle 6(1+nu)/(7+6nu); Hutchinson (2001) 6(1+nu)^2/(7+12nu+4nu^2).
  EXPECT_NEAR(cowper_shear_factor(0.3, 0.0), 7.8 / 8.8, 1e-15);
  EXPECT_NEAR(hutchinson_shear_factor_solid(0.3), 10.14 / 10.96, 1e-15);
  // Thin-walled tube limit of Cowper's formula: 2(1+nu)/(4+3nu).
  EXPECT_NEAR(cowper_shear_factor(0.3, 0.999999), 2.6 / 4.9, 1e-6);
}

TEST(BeamElement, StiffnessMatchesTimoshenkoClosedForm) {
  // Przemieniecki (1968) Timoshenko element: K(w1,w1) = 12EI/((1+Phi)L^3), K(phi1,phi1) = (4+Phi)EI/((1+Phi)L),
  // K(phi1,phi2) = (2-Phi)EI/((1+Phi)L).
  const BeamProperties p = solid(0.02, 0.01, cowper_shear_factor(kNu, 0.0));
  const double EI = kE * p.second_moment(), L = p.length, Phi = p.shear_parameter();
  ASSERT_GT(Phi, 0.05);
  const BeamElementMatrices m = beam_element(p);
  const double tol = 1e-10;
  EXPECT_NEAR(m.stiffness(0, 0) / (12 * EI / ((1 + Phi) * L * L * L)), 1.0, tol);
  EXPECT_NEAR(m.stiffness(3, 3) / ((4 + Phi) * EI / ((1 + Phi) * L)), 1.0, tol);
  EXPECT_NEAR(m.stiffness(3, 7) / ((2 - Phi) * EI / ((1 + Phi) * L)), 1.0, tol);
  EXPECT_NEAR(m.stiffness(0, 3) / (6 * EI / ((1 + Phi) * L * L)), 1.0, tol);
  // y-z plane uses theta_x = -dy/dz: same magnitudes, opposite coupling sign.
  EXPECT_NEAR(m.stiffness(1, 1), m.stiffness(0, 0), 1e-6 * m.stiffness(0, 0));
  EXPECT_NEAR(m.stiffness(1, 2), -m.stiffness(0, 3), 1e-6 * m.stiffness(0, 3));
  // Rigid translation and rigid rotation carry no strain energy.
  Eigen::Matrix<double, 8, 1> tx = Eigen::Matrix<double, 8, 1>::Zero();
  tx << 1, 0, 0, 0, 1, 0, 0, 0;
  EXPECT_NEAR((m.stiffness * tx).norm(), 0.0, 1e-6 * m.stiffness.norm());
  Eigen::Matrix<double, 8, 1> rot;  // rotation about y by 1 rad: x = z, theta_y = 1
  rot << 0, 0, 0, 1, L, 0, 0, 1;
  EXPECT_NEAR((m.stiffness * rot).norm(), 0.0, 1e-6 * m.stiffness.norm());
}

TEST(BeamModes, EulerBernoulliPinnedPinned) {
  const Rotor r = build_rotor(uniform_beam(kLength, kDiameter, 20, false, false));
  const std::vector<double> w = planar_frequencies(r, end_nodes(r));
  for (int n = 1; n <= 3; ++n) EXPECT_NEAR(w[n - 1] / eb_pinned(n), 1.0, kMeshTolerance) << "mode " << n;
}

TEST(BeamModes, EulerBernoulliFreeFree) {
  const Rotor r = build_rotor(uniform_beam(kLength, kDiameter, 20, false, false));
  const std::vector<double> w = planar_frequencies(r, {}, 1.0);
  for (int n = 1; n <= 3; ++n) EXPECT_NEAR(w[n - 1] / eb_free(n), 1.0, kMeshTolerance) << "mode " << n;
}

TEST(BeamModes, TimoshenkoPinnedPinnedThickBeam) {
  // L/d = 5: shear and rotary inertia lower the first frequency by several per cent.
  const double L = 0.25, d = 0.05, kappa = cowper_shear_factor(kNu, 0.0);
  const Rotor r = build_rotor(uniform_beam(L, d, 80, true, true));
  const std::vector<double> w = planar_frequencies(r, end_nodes(r));
  for (int n = 1; n <= 3; ++n)
    EXPECT_NEAR(w[n - 1] / timoshenko_pinned(n, L, d, kappa), 1.0, 3 * kMeshTolerance) << "mode " << n;
  const double eb1 = std::pow(M_PI / L, 2) * std::sqrt(kE * d * d / 16 / kRho);
  EXPECT_LT(w[0], 0.97 * eb1);  // the effect is really there
}

TEST(BeamModes, TimoshenkoFreeFreeThickBeam) {
  const double L = 0.25, d = 0.05, kappa = cowper_shear_factor(kNu, 0.0);
  const Rotor r = build_rotor(uniform_beam(L, d, 80, true, true));
  const std::vector<double> w = planar_frequencies(r, {}, 10.0);
  const std::vector<double> exact = timoshenko_free(3, L, d, kappa, 100.0, 50.0);
  for (int n = 0; n < 3; ++n) EXPECT_NEAR(w[n] / exact[n], 1.0, 3 * kMeshTolerance) << "mode " << n + 1;
}

TEST(BeamModes, ConvergenceOrderUnderMeshRefinement) {
  constexpr double kOrderTolerance = 0.15;
  EXPECT_NEAR(observed_order(false, 2, true, 4), 4.0, kOrderTolerance);   // Euler-Bernoulli pinned
  EXPECT_NEAR(observed_order(true, 2, true, 32), 2.0, kOrderTolerance);   // Timoshenko pinned, h << d
  EXPECT_NEAR(observed_order(true, 2, false, 32), 2.0, kOrderTolerance);  // Timoshenko free-free, h << d
}

}  // namespace
}  // namespace turbodyn
