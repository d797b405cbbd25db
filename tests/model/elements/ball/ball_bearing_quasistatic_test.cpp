// Quasi-static ball bearing: against a steady run of the element itself, bad input, and the linearisation the
// modal analysis uses.
#include "model/elements/ball/ball_bearing_quasistatic.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/elements/ball/race_geometry.h"
#include "model/io/model_file.h"
#include "model/rotor/modal.h"
#include "model/rotor/response.h"
#include "model/spec/errors.h"
#include "tests/support/ball_bearing_fixtures.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::kRpm;

// Contact loads and angles of ball j in the element's state z with the shaft at q (no tilt), from the element's
// own groove circles and Hertz constants.
QuasiStaticBall element_ball(const BallBearingElement& e, const Eigen::Vector4d& q, const std::vector<double>& z,
                             int j) {
  const double* b = z.data() + e.ball_offset(j);
  const double c = std::cos(b[0]), sn = std::sin(b[0]), side = e.spec().side;
  ball_detail::Race inner, outer;
  const BallBearingElement::GrooveCircle gi = e.inner_groove(), go = e.outer_groove();
  inner.dr = gi.radial, inner.dz = gi.axial, inner.r0 = gi.distance;
  outer.dr = go.radial, outer.dz = go.axial, outer.r0 = go.distance;
  inner.centre = ball_detail::to_orbital(q[0], q[1], 0.0, c, sn);
  outer.centre = Eigen::Vector3d(0.0, 0.0, z[e.outer_offset()]);
  ball_detail::RaceGeometry g_i, g_o;
  ball_detail::race_geometry(inner, e.pitch_radius() + b[1], b[1], b[2], g_i, true);
  ball_detail::race_geometry(outer, e.pitch_radius() + b[1], b[1], b[2], g_o, true);
  QuasiStaticBall out;
  out.azimuth = b[0];
  out.inner_load = g_i.delta > 0 ? e.inner_contact().stiffness * std::pow(g_i.delta, 1.5) : 0.0;
  out.outer_load = g_o.delta > 0 ? e.outer_contact().stiffness * std::pow(g_o.delta, 1.5) : 0.0;
  out.inner_angle = std::atan2(-side * g_i.u.z(), -g_i.u.x());
  out.outer_angle = std::atan2(side * g_o.u.z(), g_o.u.x());
  out.orbital_speed = b[3];
  return out;
}

TEST(BallBearingQuasiStatic, SteadyRunOfTheElementAgrees) {
  // The element (friction, contact damping, cage, ball dynamics) integrated at a constant 100,000 rpm with the shaft
  // centred, started at the quasi-static ball positions. After settling, the balls' contact loads and the outer
  // ring's axial position still ring (the outer ring on its spring and the balls' contact modes are lightly
  // damped and the friction keeps exciting them), so the comparison is of means over 3 ms and over the balls:
  // contact loads and angles, the orbital speed and the outer ring's axial position. With the shaft off-centre the
  // element's race friction adds a cross-coupled force (about 1e7 N/m, docs/ball-bearing.md) that the
  // quasi-static model, whose only traction is the gyroscopic one, does not have; the shaft force is therefore
  // not compared.
  constexpr double kSteadyTolerance = 0.03;  // a few %: the element's balls slip a little and carry cage forces
  const BallBearingSpec s = testing::reference_bearing();
  const BallBearingElement e("ref", s, 0, 0.0);
  const double W = 100000 * kRpm;
  const Eigen::Vector4d q(0.0, 0.0, 0.0, 0.0);
  const BallBearingQuasiStatic qs(e);
  BallBearingEquilibrium r = qs.solve(W, Eigen::Vector3d::Zero());
  Vector5d q5 = Vector5d::Zero();
  q5[0] = q[0];
  ASSERT_TRUE(qs.equilibrate(W, q5, r));
  std::vector<double> z(e.n_states());
  e.initial_states(z.data());
  for (int j = 0; j < s.n_balls; ++j) {
    z[e.ball_offset(j) + 1] = r.balls[j].rho;
    z[e.ball_offset(j) + 2] = r.balls[j].zeta;
  }
  z[e.outer_offset()] = r.outer_ring_axial;
  e.steady_states(W, z.data());
  testing::ElementIntegrator run(e, W, q, z, 1e-7, 1e-3);
  const double t_settle = 3e-3, window = 3e-3;
  constexpr int kSamples = 100;
  ASSERT_TRUE(run.advance(t_settle));
  testing::Evaluator ev(e);
  std::vector<double> zd(e.n_states());
  double f[4];
  const double v[4] = {0, 0, 0, 0};
  QuasiStaticBall mean;  // element: means over time and balls (inner_deflection holds the largest inner load)
  double fx = 0.0, zo = 0.0;
  for (int k = 1; k <= kSamples; ++k) {
    ASSERT_TRUE(run.advance(t_settle + k * window / kSamples));
    const std::vector<double> zk(run.z(), run.z() + e.n_states());
    double qmax = 0.0;
    for (int j = 0; j < s.n_balls; ++j) {
      const QuasiStaticBall b = element_ball(e, q, zk, j);
      const double w = 1.0 / (kSamples * s.n_balls);
      mean.inner_load += w * b.inner_load;
      mean.outer_load += w * b.outer_load;
      mean.inner_angle += w * b.inner_angle;
      mean.outer_angle += w * b.outer_angle;
      mean.orbital_speed += w * b.orbital_speed;
      qmax = std::max(qmax, b.inner_load);
    }
    mean.inner_deflection += qmax / kSamples;
    ev(W, q.data(), v, zk.data(), f, zd.data());
    fx += f[0] / kSamples;
    zo += zk[e.outer_offset()] / kSamples;
  }
  QuasiStaticBall ref;
  for (const QuasiStaticBall& b : r.balls) {
    const double w = 1.0 / s.n_balls;
    ref.inner_load += w * b.inner_load;
    ref.outer_load += w * b.outer_load;
    ref.inner_angle += w * b.inner_angle;
    ref.outer_angle += w * b.outer_angle;
    ref.orbital_speed += w * b.orbital_speed;
    ref.inner_deflection = std::max(ref.inner_deflection, b.inner_load);
  }
  EXPECT_NEAR(mean.inner_load / ref.inner_load, 1.0, kSteadyTolerance);
  EXPECT_NEAR(mean.outer_load / ref.outer_load, 1.0, kSteadyTolerance);
  // Angles to a few % of the free contact angle: the outer one is only about 3 deg at this speed.
  EXPECT_NEAR(mean.inner_angle, ref.inner_angle, kSteadyTolerance * s.contact_angle);
  EXPECT_NEAR(mean.outer_angle, ref.outer_angle, kSteadyTolerance * s.contact_angle);
  EXPECT_NEAR(mean.orbital_speed / ref.orbital_speed, 1.0, kSteadyTolerance);
  EXPECT_NEAR(zo / r.outer_ring_axial, 1.0, kSteadyTolerance);
  std::printf("[ steady run ] 100000 rpm, centred shaft, means (quasi-static): Q_i %.3f (%.3f) N, Q_o %.3f (%.3f) N,"
              " a_i %.3f (%.3f) deg, a_o %.3f (%.3f) deg, largest Q_i %.3f (%.3f) N, orbit %.1f (%.1f) rad/s,"
              " shaft force x %.3f (%.3f) N, z_o %.4f (%.4f) um\n",
              mean.inner_load, ref.inner_load, mean.outer_load, ref.outer_load, mean.inner_angle * 180 / M_PI,
              ref.inner_angle * 180 / M_PI, mean.outer_angle * 180 / M_PI, ref.outer_angle * 180 / M_PI,
              mean.inner_deflection, ref.inner_deflection, mean.orbital_speed, ref.orbital_speed, fx,
              r.shaft_force[0], zo * 1e6, r.outer_ring_axial * 1e6);
}

TEST(BallBearingQuasiStatic, DeepGrooveBearingWithClearanceCarriesARadialLoad) {
  // A deep-groove bearing with diametral clearance: free contact angle 10 deg (the angle at which the clearance
  // closes axially, Harris & Kotzalas 2007, ch. 2), radial clearance P_d / 2 = A (1 - cos a0) = 3.4 um, no
  // preload and no spring, so the outer ring centres itself axially. 100 N radial: at rest the inner ring first
  // crosses the clearance and only the balls near the load carry, at a contact angle of zero; at 50,000 rpm the
  // centrifugal force also presses the unloaded balls onto the outer race.
  BallBearingSpec s = testing::reference_bearing();
  s.contact_angle = 10.0 * M_PI / 180.0;
  s.preload = 0.0;
  s.preload_stiffness = 0.0;
  const BallBearingElement e("deep_groove", s, 0, 0.0);
  const double A = (s.inner_groove_ratio + s.outer_groove_ratio - 1.0) * s.ball_diameter;
  const double radial_clearance = A * (1.0 - std::cos(s.contact_angle));
  const std::vector<BallBearingEquilibrium> r =
      BallBearingQuasiStatic(e).sweep({0.0, 50000 * kRpm}, Eigen::Vector3d(100.0, 0.0, 0.0));
  for (const BallBearingEquilibrium& x : r) {
    EXPECT_NEAR(x.shaft_force[0], -100.0, 1e-5);
    EXPECT_NEAR(x.shaft_force[1], 0.0, 1e-5);
    EXPECT_GT(x.displacement[0], radial_clearance);
    EXPECT_GT(x.balls[0].inner_load, 30.0);
    EXPECT_LT(x.balls[4].inner_load, 1e-6);  // opposite the load
  }
  EXPECT_NEAR(r[0].balls[0].inner_angle, 0.0, 1.0 * M_PI / 180.0);  // radial contact (the free tilt adds ~0.5 deg)
  EXPECT_LT(r[0].balls[4].outer_load, 1e-6);  // at rest: loose (to the solver's tolerance)
  EXPECT_GT(r[1].balls[4].outer_load, 10.0);  // at speed: on the outer race
  std::printf("[ clearance ] P_d/2 %.3f um; 100 N: x %.3f um at rest (ball 0 Q %.2f N), %.3f um at 50000 rpm "
              "(ball 0 Q_i %.2f N, ball 4 Q_o %.2f N)\n",
              radial_clearance * 1e6, r[0].displacement[0] * 1e6, r[0].balls[0].inner_load,
              r[1].displacement[0] * 1e6, r[1].balls[0].inner_load, r[1].balls[4].outer_load);
}

TEST(BallBearingQuasiStatic, LoadsWithoutEquilibriumThrow) {
  const BallBearingElement e("ref", testing::reference_bearing(), 0, 0.0);
  const BallBearingQuasiStatic qs(e);
  // Far beyond the Hertz range of 4.5-mm balls.
  try {
    qs.solve(0.0, Eigen::Vector3d(2e6, 0.0, 0.0));
    ADD_FAILURE() << "no error for 2 MN";
  } catch (const QuasiStaticError& err) {
    EXPECT_NE(std::string(err.what()).find("cannot carry"), std::string::npos) << err.what();
  }
  EXPECT_THROW(qs.solve(std::nan(""), Eigen::Vector3d::Zero()), QuasiStaticError);
  // A bad geometry is refused by the element's spec check, naming the field.
  BallBearingSpec bad = testing::reference_bearing();
  bad.pitch_diameter = 0.5 * bad.ball_diameter;
  try {
    const BallBearingElement eb("bad", bad, 0, 0.0);
    ADD_FAILURE() << "no error for d_m < D";
  } catch (const std::invalid_argument& err) {
    EXPECT_NE(std::string(err.what()).find("pitch_diameter"), std::string::npos) << err.what();
  }
}

TEST(BallBearingQuasiStatic, AContactDampingRatioDampsEachContactByItsTangentStiffness) {
  // contact_damping_ratio beta: a contact's dashpot is d + beta k_c, k_c = dQ/d delta = 1.5 K delta^0.5. Preload
  // equilibrium at rest (no gravity: every ball alike), friction and pocket damping off, balls at rest, the shaft
  // moving at 0.1 mm/s in x: only the inner contacts approach, at u.v, and the dissipated power is sum c_j (u_j.v)^2,
  // so with beta alone it is beta k_c times the power with d = 1 N s/m alone.
  constexpr double kBeta = 1e-5;
  BallBearingSpec s = testing::reference_bearing();
  s.friction_static = s.friction_sliding = 0.0;
  s.pocket_damping = 0.0;
  s.contact_damping = 1.0;
  const BallBearingElement e0("d", s, 0, 0.0);
  s.contact_damping = 0.0;
  s.contact_damping_ratio = kBeta;
  const BallBearingElement e1("beta", s, 0, 0.0);
  std::vector<double> z(e0.n_states());
  e0.initial_states(z.data());
  const Eigen::Vector4d q = Eigen::Vector4d::Zero();
  const double v[4] = {1e-4, 0.0, 0.0, 0.0};
  const SpinState st{0.0, 0.0, 0.0, 0.0};
  auto w0 = e0.make_workspace(), w1 = e1.make_workspace();
  const double p0 = e0.dissipated_power(st, q.data(), v, z.data(), *w0);
  const double p1 = e1.dissipated_power(st, q.data(), v, z.data(), *w1);
  const QuasiStaticBall b = element_ball(e0, q, z, 0);
  const double K = e0.inner_contact().stiffness, delta = std::pow(b.inner_load / K, 2.0 / 3.0);
  const double k_c = 1.5 * K * std::sqrt(delta);
  ASSERT_GT(p0, 0.0);
  EXPECT_NEAR(p1 / p0, kBeta * k_c, 1e-9 * kBeta * k_c) << "k_c " << k_c;
  // Every ball alike: the other balls' inner loads are ball 0's.
  for (int j = 1; j < s.n_balls; ++j)
    EXPECT_NEAR(element_ball(e0, q, z, j).inner_load, b.inner_load, 1e-9 * b.inner_load);
  std::printf("[ contact ] preload %.1f N: inner contact %.3f N, k_c %.4g N/m, beta k_c %.1f N s/m\n", s.preload,
              b.inner_load, k_c, kBeta * k_c);
}

TEST(BallBearingQuasiStatic, AContactDampingRatioGivesTheBearingThatRatioOfItsStiffness) {
  // Kraemer's rule, damping = beta x stiffness for the whole bearing, follows from beta at every contact: dashpots
  // proportional to their springs stay so in series and in parallel. It holds for the contacts' part of K; the rest,
  // the loads' turning with the contact angles (Q d^2 delta / dq^2) and the soft preload spring in k_zz, is not
  // damped, which sets the tolerance: 1 % in the radial terms, 10 % in the tilt terms, where the preload's turning
  // with the tilt counts more (at rest, preload only and with 20 N radial).
  constexpr double kBeta = 1e-5;
  BallBearingSpec s = testing::reference_bearing();
  s.contact_damping = 0.0;
  s.contact_damping_ratio = kBeta;
  const BallBearingElement e("ref", s, 0, 0.0);
  for (const double radial : {0.0, 20.0}) {
    const BallBearingEquilibrium r = BallBearingQuasiStatic(e).solve(0.0, Eigen::Vector3d(radial, 0.0, 0.0));
    for (const int k : {0, 1, 3, 4}) {
      EXPECT_NEAR(r.damping(k, k) / (kBeta * r.stiffness(k, k)), 1.0, k < 3 ? 0.01 : 0.1)
          << "radial " << radial << " N, k " << k;
      std::printf("[ bearing ] %3.0f N radial, dof %d: c / (beta k) = %.4f\n", radial, k,
                  r.damping(k, k) / (kBeta * r.stiffness(k, k)));
    }
  }
}

TEST(BallBearingQuasiStatic, StiffnessIsSymmetricAtRestAndMatchesTheElementsStaticStiffness) {
  // At rest the bearing is conservative: K symmetric. Its radial stiffness is the element's own static value
  // (StaticStiffnessMatchesAnIndependentRigidRingCalculation, 4.958e7 N/m: Newton on the element's equations).
  constexpr double kElementStiffness = 4.958e7, kTolerance = 0.01;
  const BallBearingElement e("ref", testing::reference_bearing(), 0, 0.0);
  const BallBearingEquilibrium r = BallBearingQuasiStatic(e).solve(0.0, Eigen::Vector3d::Zero());
  EXPECT_NEAR(r.stiffness(0, 0) / kElementStiffness, 1.0, kTolerance);
  EXPECT_NEAR((r.stiffness - r.stiffness.transpose()).norm() / r.stiffness.norm(), 0.0, 1e-5);
  EXPECT_NEAR(r.stiffness(3, 3) / 365.2, 1.0, kTolerance);  // the element's tilt stiffness (N m/rad)
  // Contact damping: positive semi-definite, and for 16 contacts of d = 15 N s/m at about 15 deg of order Z d.
  const Eigen::SelfAdjointEigenSolver<Matrix5d> eig(r.damping);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
  EXPECT_GT(r.damping(0, 0), 0.0);
  std::printf("[ at rest ] k_xx %.5g N/m, k_zz %.5g N/m, k_tilt %.5g N m/rad, c_xx %.4g N s/m, c_zz %.4g N s/m\n",
              r.stiffness(0, 0), r.stiffness(2, 2), r.stiffness(3, 3), r.damping(0, 0), r.damping(2, 2));
}

TEST(BallBearingQuasiStatic, ModalAnalysisOfTheReferenceBallRotor) {
  // examples/reference_ball.toml with its ball bearings linearised at every speed: the stiffness at rest is the
  // element's static stiffness, and the critical speeds are finite and positive.
  constexpr double kElementStiffness = 4.958e7, kTolerance = 0.01;
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  Rotor rotor = build_rotor(spec);
  ASSERT_TRUE(rotor.bearings.empty());
  add_ball_bearing_linearisations(spec, rotor);
  ASSERT_EQ(rotor.bearings.size(), 2u);
  for (const LinearBearing& b : rotor.bearings) {
    Eigen::Matrix4d k, c;
    b.coefficients(0.0, k, c);
    EXPECT_NEAR(k(0, 0) / kElementStiffness, 1.0, kTolerance) << b.name;
    EXPECT_NEAR(k(1, 1) / kElementStiffness, 1.0, kTolerance) << b.name;
  }
  std::vector<double> speeds;
  for (int i = 0; i <= 6; ++i) speeds.push_back(i * 25000 * kRpm);
  const Campbell c = campbell_diagram(rotor, speeds, {1.0}, ModalOptions{6});
  ASSERT_FALSE(c.critical.empty());
  for (const CriticalSpeed& cs : c.critical) {
    EXPECT_TRUE(std::isfinite(cs.speed) && cs.speed > 0.0);
    std::printf("[ modal ] 1x %s branch %d: %.0f rpm (%.1f Hz), zeta %.4g\n", to_string(cs.whirl).c_str(),
                cs.branch + 1, cs.speed / kRpm, cs.frequency, cs.damping_ratio);
  }
  // The unbalance response on the same linearisation (`turbodyn response`) peaks at the forward critical speeds:
  // the largest whirl of a wheel within 1 % of each crossing lies at it to 0.05 % (steps of 0.025 %).
  for (const CriticalSpeed& cs : c.critical) {
    if (cs.whirl != Whirl::Forward || cs.order != 1.0) continue;
    double best = 0.0, at = 0.0;
    for (int i = -40; i <= 40; ++i) {
      const double w = cs.speed * (1.0 + 2.5e-4 * i);
      const SteadyResponse r = unbalance_response(rotor, w);
      for (const RigidDisk& d : rotor.disks) {
        const double a = major_semi_axis(r.q(rotor.dof(d.node, kX)), r.q(rotor.dof(d.node, kY)));
        if (a > best) best = a, at = w;
      }
    }
    EXPECT_NEAR(at / cs.speed, 1.0, 5e-4) << "branch " << cs.branch;
    std::printf("[ response ] peak at %.1f Hz (%.3g m), critical %.1f Hz\n", at / (2 * M_PI), best, cs.frequency);
  }
  // A squeeze-film damper stays refused, saying that it is nonlinear.
  const MachineSpec sfd = load_model(testing::source_dir() + "/examples/reference_ball_sfd.toml");
  Rotor r2 = build_rotor(sfd);
  try {
    add_ball_bearing_linearisations(sfd, r2);
    ADD_FAILURE() << "no error for a damper";
  } catch (const ModelError& err) {
    EXPECT_NE(std::string(err.what()).find("nonlinear"), std::string::npos) << err.what();
  }
}

}  // namespace
}  // namespace turbodyn
