// Quasi-static ball bearing against references: the public deep-groove load-deflection number (docs/references.md
// §5) and an independent high-speed calculation in the classic Jones/Harris form, written here.
#include "model/elements/ball/ball_bearing_quasistatic.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "tests/support/ball_bearing_fixtures.h"
#include "tests/support/test_support.h"
#include "model/spec/constants.h"

namespace turbodyn {
namespace {

using testing::deep_groove_reference;


// The bearing of examples/reference_ball.toml (the compressor-side one; the turbine side is its mirror image).
BallBearingSpec example_bearing() {
  const MachineSpec m = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  for (const BearingSpec& b : m.bearings)
    if (b.name == "compressor") return b.ball;
  ADD_FAILURE() << "no bearing 'compressor' in examples/reference_ball.toml";
  return BallBearingSpec{};
}

// Jones (1960) / Harris & Kotzalas (2007, Advanced Concepts, ch. "high-speed ball bearings") in their own
// variables, independently of the solver: rigid rings, the inner ring displaced radially by delta_r along x and
// held axially, the outer ring's axial travel t (towards the contacts) on the preload spring. Per ball j at
// psi_j = 2 pi j / Z the ball centre is (X1, X2) from the outer groove-curvature centre (axial towards the inner
// groove centre, radial outwards), and the inner groove centre is at (A1, A2) = (A sin a0 + t, A cos a0 +
// delta_r cos psi_j), A = (f_i + f_o - 1) D (the planar form: the ring's tangential motion is ignored); a tilt
// theta_y of the inner ring shifts A1 by -side theta_y R_i cos psi_j (R_i the inner groove centres' radius). Then
//   delta_o = sqrt(X1^2 + X2^2) - (f_o - 1/2) D,   sin a_o = X1 / ((f_o - 1/2) D + delta_o), cos a_o likewise X2
//   delta_i = sqrt((A1-X1)^2 + (A2-X2)^2) - (f_i - 1/2) D,  sin a_i = (A1 - X1) / (...), cos a_i = (A2 - X2) / (...)
//   Q = K delta^1.5 with the Hertz constants of each race,
// and the two equations of each ball, outer-race control (lambda_o = 2, lambda_i = 0):
//   Q_i sin a_i - Q_o sin a_o - (2 M_g / D) cos a_o = 0
//   Q_i cos a_i - Q_o cos a_o + (2 M_g / D) sin a_o + F_c = 0
// with F_c = (1/2) m d_m w_m^2, M_g = J w_R w_m sin(beta), J = m D^2 / 10, and Harris's outer-race-control
// kinematics (gamma = D / d_m):
//   tan(beta) = sin a_o / (cos a_o + gamma),
//   w_m / w = (1 - gamma cos a_i) / (1 + cos(a_i - a_o)),
//   w_R / w = 1 / (gamma cos(beta) [(cos a_o + tan(beta) sin a_o) / (1 + gamma cos a_o)
//                                   + (cos a_i + tan(beta) sin a_i) / (1 - gamma cos a_i)]).
// The outer ring: Z-sum of (Q_o sin a_o + (2 M_g / D) cos a_o) = F_p - k_p t. Radial force on the inner ring:
// F_x = -sum Q_i cos a_i cos psi_j.
struct JonesHarris {
  BallBearingSpec s;
  double Ki = 0.0, Ko = 0.0;
  struct Ball {
    double Qi, Qo, ai, ao;
  };
  struct Result {
    std::vector<Ball> balls;
    double fx = 0.0, travel = 0.0;
    Eigen::VectorXd unknowns;
  };

  // start: a previous solution's unknowns (X1, X2 per ball, t), else every ball on the line of groove centres.
  Result solve(double w, double delta_r, const Eigen::VectorXd* start = nullptr, double theta = 0.0) const {
    const int Z = s.n_balls;
    const double D = s.ball_diameter, dm = s.pitch_diameter, gamma = D / dm;
    const double ri = (s.inner_groove_ratio - 0.5) * D, ro = (s.outer_groove_ratio - 0.5) * D, A = ri + ro;
    const double m = s.ball_density * M_PI * D * D * D / 6.0, J = m * D * D / 10.0;
    const double Ri = 0.5 * dm + ri * std::cos(s.contact_angle);  // radius of the inner groove-centre circle
    const int n = 2 * Z + 1;
    // Start: every ball on the line of groove centres at the free angle, touching the outer race.
    Eigen::VectorXd x(n);
    for (int j = 0; j < Z; ++j) x(2 * j) = ro * std::sin(s.contact_angle), x(2 * j + 1) = ro * std::cos(s.contact_angle);
    x(n - 1) = 0.0;
    if (start) x = *start;
    std::vector<Ball> balls(Z);
    const auto residual = [&](const Eigen::VectorXd& v, Eigen::VectorXd& r, double* fx) {
      r.resize(n);
      const double t = v(n - 1);
      double axial = 0.0;
      if (fx) *fx = 0.0;
      for (int j = 0; j < Z; ++j) {
        const double psi = 2 * M_PI * j / Z;
        const double A1 = A * std::sin(s.contact_angle) + t - s.side * theta * Ri * std::cos(psi), A2 = A * std::cos(s.contact_angle) + delta_r * std::cos(psi);
        const double X1 = v(2 * j), X2 = v(2 * j + 1);
        const double Lo = std::hypot(X1, X2), Li = std::hypot(A1 - X1, A2 - X2);
        const double dOut = Lo - ro, dIn = Li - ri;
        const double Qo = dOut > 0 ? Ko * std::pow(dOut, 1.5) : 0.0, Qi = dIn > 0 ? Ki * std::pow(dIn, 1.5) : 0.0;
        const double sao = X1 / Lo, cao = X2 / Lo, sai = (A1 - X1) / Li, cai = (A2 - X2) / Li;
        const double ao = std::atan2(sao, cao), ai = std::atan2(sai, cai);
        const double wm = w * (1 - gamma * cai) / (1 + std::cos(ai - ao));
        const double tb = sao / (cao + gamma), beta = std::atan(tb);
        const double wR = w == 0.0 ? 0.0
                                   : w / (gamma * std::cos(beta) *
                                          ((cao + tb * sao) / (1 + gamma * cao) + (cai + tb * sai) / (1 - gamma * cai)));
        const double Mg = J * wR * wm * std::sin(beta), Fc = 0.5 * m * dm * wm * wm;
        r(2 * j) = Qi * sai - Qo * sao - 2 * Mg / D * cao;
        r(2 * j + 1) = Qi * cai - Qo * cao + 2 * Mg / D * sao + Fc;
        axial += Qo * sao + 2 * Mg / D * cao;
        if (fx) *fx -= Qi * cai * std::cos(psi);
        balls[j] = {Qi, Qo, ai, ao};
      }
      r(n - 1) = axial - (s.preload - s.preload_stiffness * t);
    };
    Eigen::VectorXd r(n), r1(n), r2(n);
    Eigen::MatrixXd Jac(n, n);
    for (int it = 0; it < 100; ++it) {
      residual(x, r, nullptr);
      if (r.cwiseAbs().maxCoeff() < 1e-11) break;
      for (int k = 0; k < n; ++k) {
        const double h = 1e-12, saved = x(k);
        x(k) = saved + h;
        residual(x, r1, nullptr);
        x(k) = saved - h;
        residual(x, r2, nullptr);
        x(k) = saved;
        Jac.col(k) = (r1 - r2) / (2 * h);
      }
      Eigen::VectorXd dx = Jac.colPivHouseholderQr().solve(-r);
      double a = 1.0;
      for (int k = 0; k < 30; ++k, a *= 0.5) {
        residual(x + a * dx, r1, nullptr);
        if (r1.cwiseAbs().maxCoeff() < r.cwiseAbs().maxCoeff()) break;
      }
      x += a * dx;
    }
    Result res;
    residual(x, r, &res.fx);
    EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-9) << "Jones/Harris Newton at " << w << " rad/s, delta_r " << delta_r;
    res.balls = balls;
    res.travel = x(n - 1);
    res.unknowns = x;
    return res;
  }
  // Radial stiffness -dF_x/d delta_r at the centred ring by central differences.
  double radial_stiffness(double w) const {
    const double h = 2e-9;
    const Result centred = solve(w, 0.0);
    return -(solve(w, h, &centred.unknowns).fx - solve(w, -h, &centred.unknowns).fx) / (2 * h);
  }
};

TEST(BallBearingQuasiStatic, DeepGrooveReferenceAtRest) {
  // docs/references.md §5: Z = 7, D = 11.5 mm, d_m = 43.5 mm, f = 0.52 / 0.53, zero clearance, E = 210 GPa,
  // nu = 0.3: a radial load of 1000 N displaces the rigid rings by 15.110 um.
  constexpr double kReferenceTolerance = 0.005;  // the reference is given to 5 digits; the brief's 0.5 %
  const BallBearingElement e("deep_groove", deep_groove_reference(), 0, 0.0);
  const BallBearingQuasiStatic qs(e);
  const BallBearingEquilibrium r = qs.solve(0.0, Eigen::Vector3d(1000.0, 0.0, 0.0));
  EXPECT_NEAR(r.displacement[0] / 15.110e-6, 1.0, kReferenceTolerance) << r.displacement.transpose();
  EXPECT_NEAR(r.displacement[1], 0.0, 1e-12);
  EXPECT_NEAR(r.shaft_force[0], -1000.0, 1e-6);
  // The ball under the load carries the most: Q_max = 4.37 F / Z for zero clearance (Stribeck; Harris &
  // Kotzalas 2007, ch. 7) is only a rule of thumb, so the check is the force balance itself.
  // The planar sum of the ball loads; the solver's shaft force also has the contacts' small tangential parts
  // (the inner ring's offset across each azimuth plane), about 3e-4 of the load here.
  double sum = 0.0;
  for (const QuasiStaticBall& b : r.balls) sum += b.inner_load * std::cos(b.inner_angle) * std::cos(b.azimuth);
  EXPECT_NEAR(sum / 1000.0, 1.0, 1e-3);
  std::printf("[ deep groove ] 1000 N -> %.4f um (reference 15.110), Q_max %.2f N (Stribeck 4.37 F/Z = %.1f N)\n",
              r.displacement[0] * 1e6, r.balls[0].inner_load, 4.37 * 1000 / 7);
}

TEST(BallBearingQuasiStatic, MatchesAnIndependentJonesHarrisCalculation) {
  // Reference bearing (examples/reference_ball.toml), centred shaft, preload 40 N, at rest and at 100,000 rpm:
  // contact angles and loads of the balls and the radial stiffness.
  constexpr double kAtRest = 0.01, kAtSpeed = 0.02;  // the brief's 1 % and 2 %
  const BallBearingSpec s = example_bearing();
  const BallBearingElement e("ref", s, 0, 0.0);
  const BallBearingQuasiStatic qs(e);
  const JonesHarris jh{s, e.inner_contact().stiffness, e.outer_contact().stiffness};
  const std::vector<BallBearingEquilibrium> sw = qs.sweep({0.0, 100000 * kRpmToRadPerS}, Eigen::Vector3d::Zero());
  for (int k = 0; k < 2; ++k) {
    const BallBearingEquilibrium& r = sw[k];
    const double tol = k == 0 ? kAtRest : kAtSpeed;
    const JonesHarris::Result ref = jh.solve(r.speed, 0.0);
    const double k_ref = jh.radial_stiffness(r.speed);
    for (int j = 0; j < s.n_balls; ++j) {
      const QuasiStaticBall& b = r.balls[j];
      EXPECT_NEAR(b.inner_load / ref.balls[j].Qi, 1.0, tol) << "ball " << j << " at " << r.speed << " rad/s";
      EXPECT_NEAR(b.outer_load / ref.balls[j].Qo, 1.0, tol) << "ball " << j;
      EXPECT_NEAR(b.inner_angle / ref.balls[j].ai, 1.0, tol) << "ball " << j;
      EXPECT_NEAR(b.outer_angle / ref.balls[j].ao, 1.0, tol) << "ball " << j;
    }
    EXPECT_NEAR(r.stiffness(0, 0) / k_ref, 1.0, tol);
    EXPECT_NEAR(r.stiffness(1, 1) / k_ref, 1.0, tol);
    EXPECT_NEAR(-s.side * r.outer_ring_axial / ref.travel, 1.0, tol);
    std::printf("[ jones-harris ] %6.0f rpm: Q_i %.3f (%.3f) N, Q_o %.3f (%.3f) N, a_i %.3f (%.3f) deg, a_o %.3f"
                " (%.3f) deg, k_xx %.5g (%.5g) N/m, k_yy %.5g, outer travel %.4f (%.4f) um, cage ratio %.5f\n",
                r.speed / kRpmToRadPerS, r.balls[0].inner_load, ref.balls[0].Qi, r.balls[0].outer_load, ref.balls[0].Qo,
                r.balls[0].inner_angle * 180 / M_PI, ref.balls[0].ai * 180 / M_PI, r.balls[0].outer_angle * 180 / M_PI,
                ref.balls[0].ao * 180 / M_PI, r.stiffness(0, 0), k_ref, r.stiffness(1, 1),
                -s.side * r.outer_ring_axial * 1e6, ref.travel * 1e6, r.speed > 0 ? r.cage_speed / r.speed : 0.0);
  }
  // Under a radial load the balls differ: 100 N along +x at 100,000 rpm, ball by ball, at the solver's inner-ring
  // displacement and tilt (an angular-contact bearing tilts under a radial load when free to).
  const BallBearingEquilibrium r = qs.solve(100000 * kRpmToRadPerS, Eigen::Vector3d(100.0, 0.0, 0.0));
  const JonesHarris::Result centred = jh.solve(r.speed, 0.0);
  const JonesHarris::Result ref = jh.solve(r.speed, r.displacement[0], &centred.unknowns, r.displacement[4]);
  EXPECT_NEAR(-ref.fx / 100.0, 1.0, kAtSpeed) << "Jones/Harris radial force at the solver's displacement";
  for (int j = 0; j < s.n_balls; ++j) {
    EXPECT_NEAR(r.balls[j].inner_load, ref.balls[j].Qi, kAtSpeed * ref.balls[0].Qi) << "ball " << j;
    EXPECT_NEAR(r.balls[j].inner_angle / ref.balls[j].ai, 1.0, kAtSpeed) << "ball " << j;
  }
  std::printf("[ jones-harris ] 100 N at 100000 rpm: x %.4f um, theta_y %.3e rad, Jones/Harris force there %.3f N;"
              " ball 0 Q_i %.3f"
              " (%.3f) N, a_i %.3f (%.3f) deg; ball 4 Q_i %.3f (%.3f) N\n",
              r.displacement[0] * 1e6, r.displacement[4], -ref.fx, r.balls[0].inner_load, ref.balls[0].Qi,
              r.balls[0].inner_angle * 180 / M_PI, ref.balls[0].ai * 180 / M_PI, r.balls[4].inner_load, ref.balls[4].Qi);
}

TEST(BallBearingQuasiStatic, LoadDeflectionCurveMatchesTheReferencesAndHardens) {
  // The load-deflection curve (tilt held, as the test's planar Jones/Harris calculation holds it): the deep-groove
  // reference of docs/references.md §5 (15.110 um under 1000 N, 0.5 %), and the reference bearing against Jones/
  // Harris at rest (1 %) and at 100,000 rpm (2 %) from the centred ring into the Hertzian hardening of the
  // resonance of variant II (docs/ball-bearing.md: about 3,000 N at the compressor bearing, 50 um). The tangent at
  // zero travel is the linearisation's k_xx.
  {
    const BallBearingElement e("deep_groove", deep_groove_reference(), 0, 0.0);
    const std::vector<LoadDeflectionPoint> c = BallBearingQuasiStatic(e).load_deflection(0.0, {15.110e-6});
    std::printf("[ load-deflection ] deep groove: 15.110 um -> %.2f N (reference 1000 N)\n", c[0].load);
    EXPECT_NEAR(c[0].load / 1000.0, 1.0, 0.005);
  }
  const BallBearingSpec s = example_bearing();
  const BallBearingElement e("ref", s, 0, 0.0);
  const BallBearingQuasiStatic qs(e);
  const JonesHarris jh{s, e.inner_contact().stiffness, e.outer_contact().stiffness};
  const std::vector<double> travel = {0.0, 2e-6, 10e-6, 30e-6, 50e-6};
  for (const double w : {0.0, 100000 * kRpmToRadPerS}) {
    const double tol = w == 0.0 ? 0.01 : 0.02;
    const BallBearingEquilibrium centred = qs.solve(w, Eigen::Vector3d::Zero());
    const std::vector<LoadDeflectionPoint> c = qs.load_deflection(w, travel, &centred);
    ASSERT_EQ(c.size(), travel.size());
    EXPECT_NEAR(c[0].load, 0.0, 1e-6);
    EXPECT_NEAR(c[0].tangent / centred.stiffness(0, 0), 1.0, 1e-3);
    JonesHarris::Result ref = jh.solve(w, 0.0);
    for (std::size_t i = 1; i < c.size(); ++i) {
      for (double d = travel[i - 1] + 1e-6; d < travel[i]; d += 1e-6) ref = jh.solve(w, d, &ref.unknowns);
      ref = jh.solve(w, travel[i], &ref.unknowns);
      std::printf("[ load-deflection ] %6.0f rpm, %4.1f um: %8.2f N (Jones/Harris %8.2f), secant %.4g, tangent %.4g "
                  "N/m, Q_max %.1f N\n",
                  w / kRpmToRadPerS, travel[i] * 1e6, c[i].load, -ref.fx, c[i].secant, c[i].tangent,
                  c[i].max_contact_load);
      EXPECT_NEAR(c[i].load / -ref.fx, 1.0, tol) << travel[i] * 1e6 << " um at " << w / kRpmToRadPerS << " rpm";
      EXPECT_NEAR(c[i].secant, c[i].load / travel[i], 1e-9 * c[i].secant);
      EXPECT_NEAR(c[i].cross_load, 0.0, 1e-6 * c[i].load);
    }
    // Hertzian hardening: at 50 um the secant is well above the centred stiffness at speed, where the centrifugal
    // forces have unloaded the inner contacts.
    if (w > 0.0) {
      EXPECT_GT(c.back().secant, 3.0 * c[0].tangent);
    }
  }
  // A travel below the differencing step (1 nm) is differenced centrally too: its tangent is the centred one.
  const std::vector<LoadDeflectionPoint> tiny = qs.load_deflection(46000 * kRpmToRadPerS, {0.0, 1e-9});
  EXPECT_NEAR(tiny[1].tangent / tiny[0].tangent, 1.0, 1e-3);
  EXPECT_THROW(qs.load_deflection(0.0, {2e-6, 1e-6}), std::invalid_argument);
  const BallBearingEquilibrium loaded = qs.solve(0.0, Eigen::Vector3d(50.0, 0.0, 0.0));
  EXPECT_THROW(qs.load_deflection(0.0, {1e-6}, &loaded), std::invalid_argument);
  EXPECT_THROW(qs.load_deflection(0.0, {-1e-6}), std::invalid_argument);
  EXPECT_THROW(qs.load_deflection(0.0, {1e-3}), QuasiStaticError);  // a contact deflection far beyond 2 % of D
}

}  // namespace
}  // namespace turbodyn
