// Ball bearing as a multibody element: forces as the gradient of the contact potential, energy conservation
// without friction and damping, the energy balance with them, evaluation caching, bad input.
#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/elements/ball/race_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "tests/support/ball_bearing_fixtures.h"

namespace turbodyn {
namespace {

using namespace testing;  // the ball-bearing fixtures

// ------------------------------------------------------------------------------------------------ tests

TEST(BallBearing, ShaftForcesAreTheGradientOfThePotentialWithoutFrictionAndDamping) {
  // Conservative contacts: generalised forces on the shaft = -dV/dq (central differences, tolerance sqrt(h)).
  BallBearingSpec s = reference_bearing();
  s.friction_static = s.friction_sliding = 0.0;
  s.contact_damping = s.pocket_damping = 0.0;
  const BallBearingElement e("ref", s, 0, 9.81);
  std::vector<double> z(e.n_states()), zd(e.n_states());
  e.initial_states(z.data());
  for (int j = 0; j < s.n_balls; ++j) z[e.ball_offset(j)] += 0.1 * j;  // off the symmetric positions
  Evaluator eval(e);
  const double q[4] = {1.5e-6, -0.7e-6, 3e-5, -2e-5}, v[4] = {0, 0, 0, 0};
  double f[4];
  eval(1000.0, q, v, z.data(), f, zd.data());
  for (int i = 0; i < 4; ++i) {
    const double h = i < 2 ? 1e-9 : 1e-7;
    double qp[4], qm[4];
    std::copy(q, q + 4, qp);
    std::copy(q, q + 4, qm);
    qp[i] += h;
    qm[i] -= h;
    const double grad = (e.potential_energy(qp, z.data()) - e.potential_energy(qm, z.data())) / (2 * h);
    EXPECT_NEAR(f[i], -grad, 1e-4 * (std::abs(grad) + 1e-3)) << "dof " << i;
  }
}

TEST(BallBearing, EnergyIsConservedWithoutFrictionAndDamping) {
  // With friction and damping off and the shaft held (spinning at constant speed), nothing does work on the
  // bearing's bodies: kinetic + potential (Hertz, pockets, preload spring, gravity) stays constant.
  BallBearingSpec s = reference_bearing();
  s.friction_static = s.friction_sliding = 0.0;
  s.contact_damping = s.pocket_damping = 0.0;
  s.outer_ring_mode = OuterRingMode::Spring;
  s.outer_ring_damping = 0.0;
  const BallBearingElement e("ref", s, 0, 9.81);
  const double W = 30000 * kRpm;
  std::vector<double> z(e.n_states());
  e.initial_states(z.data());
  e.steady_states(W, z.data());
  const Eigen::Vector4d q(2e-6, -1e-6, 0.0, 0.0);
  const auto energy = [&](const double* zz) { return e.kinetic_energy(zz) + e.potential_energy(q.data(), zz); };
  ElementIntegrator in(e, W, q, z, 1e-10, 1e-5);
  const double E0 = energy(z.data());
  double v_min = 1e30, v_max = -1e30, drift = 0.0;
  for (int k = 1; k <= 200; ++k) {
    ASSERT_TRUE(in.advance(k * 1e-5));
    const double V = e.potential_energy(q.data(), in.z());
    v_min = std::min(v_min, V), v_max = std::max(v_max, V);
    drift = std::max(drift, std::abs(energy(in.z()) - E0));
  }
  // Tolerance: 1e-3 of the potential energy swing (the energy the contacts exchange with the motion), far above
  // the integrator's error at rtol 1e-10 and far below any modelling inconsistency.
  EXPECT_LT(drift, 1e-3 * (v_max - v_min)) << "drift " << drift << " J, swing " << v_max - v_min << " J, E0 " << E0;
  std::printf("[ energy ] E0 %.6e J, potential swing %.3e J, max drift %.3e J over 2 ms, %ld steps\n", E0,
              v_max - v_min, drift, in.steps());
}

TEST(BallBearing, PowersAndProbesAreThoseOfTheirOwnStateWhateverWasEvaluatedBefore) {
  // The element keeps the loads of its last engine evaluation for the powers and probes at the same state; at
  // any other state they must be evaluated anew. Compared with a workspace that has seen nothing.
  const BallBearingElement e("ref", reference_bearing(), 0, 9.81);
  const double W = 60000 * kRpm;
  const SpinState s{0.0, W, 0.0, 0.0};
  std::vector<double> z1(e.n_states()), zdot(e.n_states());
  e.initial_states(z1.data());
  e.steady_states(W, z1.data());
  std::vector<double> z2 = z1;
  z2[e.ball_offset(3) + 4] += 2e-3;  // ball 3 moving radially: more damping in its contacts
  const double q[4] = {3e-6, -2e-6, 0.0, 0.0}, v[4] = {0.01, 0.0, 0.0, 0.0};
  auto ws = e.make_workspace();
  const auto fresh = [&](const std::vector<double>& z, int what) {
    auto w = e.make_workspace();
    std::vector<double> out(e.probes().size());
    if (what == 0) return e.dissipated_power(s, q, v, z.data(), *w);
    if (what == 1) return e.drive_power(s, q, v, z.data(), *w);
    e.eval_probes(s, q, v, z.data(), *w, out.data());
    return out[0];
  };
  for (const auto* z : {&z1, &z2}) {
    double f[4] = {0, 0, 0, 0};
    e.calc_and_add_forces(s, q, v, z1.data(), *ws, f, zdot.data());
    std::vector<double> out(e.probes().size());
    EXPECT_EQ(e.dissipated_power(s, q, v, z->data(), *ws), fresh(*z, 0));
    EXPECT_EQ(e.drive_power(s, q, v, z->data(), *ws), fresh(*z, 1));
    e.eval_probes(s, q, v, z->data(), *ws, out.data());
    EXPECT_EQ(out[0], fresh(*z, 2));
  }
  EXPECT_NE(fresh(z1, 0), fresh(z2, 0));
}

// With friction and damping on: E(t) - E(0) = work of the drive - dissipated energy, the drive holding the rotor
// speed against the bearing's torque on the shaft (inner-race friction). The two powers are integrated as extra
// states by the same integrator. Fixed outer ring, so calc_bearing covers every state.
void check_dissipation_balances_the_energy(const BallBearingSpec& s) {
  const BallBearingElement e("ref", s, 0, 9.81);
  const double W = 30000 * kRpm;
  std::vector<double> z(e.n_states());
  e.initial_states(z.data());
  e.steady_states(W, z.data());
  const Eigen::Vector4d q(1e-6, 0.0, 0.0, 0.0);
  const double v[4] = {0, 0, 0, 0};
  const auto energy = [&](const double* zz) { return e.kinetic_energy(zz) + e.potential_energy(q.data(), zz); };
  auto ws = e.make_workspace();
  ElementIntegrator in(e, W, q, z, 1e-8, 1e-4, true);
  const double E0 = energy(z.data());
  double p_min = 1e30;
  const double dt = 2e-6;
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_TRUE(in.advance(k * dt));
    p_min = std::min(p_min, e.dissipated_power(SpinState{0.0, W, 0.0, 0.0}, q.data(), v, in.z(), *ws));
  }
  EXPECT_GE(p_min, 0.0);
  const double lost = in.dissipated(), work = in.drive_work();
  const double balance = energy(in.z()) - E0 + lost - work;
  // Tolerance: 1e-4 of the energy dissipated, well above the integration error at rtol 1e-8.
  EXPECT_LT(std::abs(balance), 1e-4 * lost) << "E " << energy(in.z()) - E0 << " lost " << lost << " work " << work;
  std::printf("[ balance ] 2 ms at 30000 rpm: dissipated %.4e J (mean %.3f W), drive work %.4e J, kinetic+potential "
              "%+.4e J, residual %.2e J\n",
              lost, lost / 2e-3, work, energy(in.z()) - E0, balance);
}

TEST(BallBearing, DissipationIsNonNegativeAndBalancesTheEnergy) { check_dissipation_balances_the_energy(reference_bearing()); }

TEST(BallBearing, LubricatedTractionDissipatesAndBalancesTheEnergy) {
  BallBearingSpec s = reference_bearing();
  s.traction_law = TractionLaw::Eyring;
  s.lubricant_viscosity = 0.01;
  check_dissipation_balances_the_energy(s);
}

TEST(BallBearing, PowerFlowProbesSplitTheShaftPowerAndTheLosses) {
  // The power-flow probes: the inner-race normal and friction parts of the power on the shaft's lateral motion add
  // up to the generalised shaft forces times the shaft's velocities (x, y and tilt rates), and without contact and
  // pocket damping the three friction losses add up to the dissipated power. Moving, tilted shaft with balls off
  // their no-slip speeds and ball 2 pressed into its pocket, so that every channel is non-zero.
  BallBearingSpec spec = reference_bearing();
  spec.contact_damping = 0.0;
  spec.pocket_damping = 0.0;
  const BallBearingElement e("ref", spec, 0, 9.81);
  const double W = 60000 * kRpm;
  const SpinState s{0.0, W, 0.0, 0.0};
  std::vector<double> z(e.n_states()), zdot(e.n_states());
  e.initial_states(z.data());
  e.steady_states(W, z.data());
  for (int j = 0; j < spec.n_balls; ++j) z[e.ball_offset(j) + 6] += 50.0 * (j + 1);
  z[e.ball_offset(2) + 0] += 1.2 * spec.pocket_clearance / (0.5 * spec.pitch_diameter);
  const double q[4] = {2e-6, -1e-6, 2e-5, -1e-5}, v[4] = {0.02, -0.01, 3.0, 2.0};
  BallBearingLoads loads;
  e.calc_bearing(s, q, v, z.data(), OuterRingKinematics{}, loads, zdot.data());
  const double lateral = loads.shaft[0] * v[0] + loads.shaft[1] * v[1] + loads.shaft[2] * v[2] + loads.shaft[3] * v[3];
  EXPECT_NE(loads.shaft_power_normal, 0.0);
  EXPECT_NE(loads.shaft_power_friction, 0.0);
  EXPECT_NEAR(loads.shaft_power_normal + loads.shaft_power_friction, lateral, 1e-9 * std::abs(lateral) + 1e-15);
  EXPECT_GT(loads.friction_loss_inner, 0.0);
  EXPECT_GT(loads.friction_loss_outer, 0.0);
  EXPECT_GT(loads.friction_loss_pocket, 0.0);
  const double losses = loads.friction_loss_inner + loads.friction_loss_outer + loads.friction_loss_pocket;
  EXPECT_NEAR(losses, loads.dissipated_power, 1e-9 * loads.dissipated_power);
  // The probes report the same numbers.
  auto ws = e.make_workspace();
  const std::vector<ProbeInfo> info = e.probes();
  std::vector<double> out(info.size());
  e.eval_probes(s, q, v, z.data(), *ws, out.data());
  const auto probe = [&](const std::string& name) {
    for (std::size_t i = 0; i < info.size(); ++i)
      if (info[i].name == name) return out[i];
    ADD_FAILURE() << "no probe " << name;
    return 0.0;
  };
  EXPECT_EQ(probe("shaft_power_normal"), loads.shaft_power_normal);
  EXPECT_EQ(probe("shaft_power_friction"), loads.shaft_power_friction);
  EXPECT_EQ(probe("friction_loss_inner"), loads.friction_loss_inner);
  EXPECT_EQ(probe("friction_loss_outer"), loads.friction_loss_outer);
  EXPECT_EQ(probe("friction_loss_pocket"), loads.friction_loss_pocket);
  // Ball set: ball 2 moved along its orbit by the angle d, all others equally spaced on the pitch radius R (their
  // rho is the preload equilibrium's, the same for all): the mass centre lies |R (e(psi + d) - e(psi))| / Z =
  // 2 R sin(d / 2) / Z off the axis. The cage probes are its centre's states.
  const double R = 0.5 * spec.pitch_diameter + z[e.ball_offset(0) + 1];
  const double d = 1.2 * spec.pocket_clearance / (0.5 * spec.pitch_diameter);
  EXPECT_NEAR(probe("ball_set_offset"), 2.0 * R * std::sin(0.5 * d) / spec.n_balls, 1e-12);
  z[e.cage_offset() + 0] = 3e-6;
  z[e.cage_offset() + 1] = -2e-6;
  e.eval_probes(s, q, v, z.data(), *ws, out.data());
  EXPECT_EQ(probe("cage_x"), 3e-6);
  EXPECT_EQ(probe("cage_y"), -2e-6);
}

TEST(BallBearing, Eq23FrictionLawIsTheClosedForm) {
  // mu(v) / v of the paper's Eq. 23 against the closed form with std::tanh, on both sides of each branch of the
  // evaluation (v / v2 = 1e-4, 0.5, 20) and over nine decades of slip; mu_0 / v2 at v = 0.
  const double mu0 = 0.10, mur = 0.05, v1 = 0.05, v2 = 0.005;
  const auto closed = [&](double v) { return (mur + (mu0 - mur) * std::exp(-v / v1)) * std::tanh(v / v2) / v; };
  EXPECT_DOUBLE_EQ(ball_detail::eq23_mu_over_slip(0.0, mu0, mur, v1, v2), mu0 / v2);
  std::vector<double> slips;
  for (double x : {1e-4, 0.5, 20.0})
    for (double f : {1.0 - 1e-12, 1.0, 1.0 + 1e-12, 0.9, 1.1}) slips.push_back(x * f * v2);
  for (double v = 1e-9; v < 10.0; v *= 1.37) slips.push_back(v);
  for (double v : slips) {
    const double got = ball_detail::eq23_mu_over_slip(v, mu0, mur, v1, v2), want = closed(v);
    // Below v / v2 = 1e-4 the series 1 - x^2/3 of tanh(x)/x is exact to 2e-17; elsewhere a few ulp.
    EXPECT_NEAR(got, want, 2e-15 * want) << "slip " << v << " m/s";
  }
}

TEST(BallBearing, LoadCubeRootFromTheHertzApproachIsStdCbrt) {
  // The spin moment's contact radius needs Q^(1/3); load_cbrt starts from Q_H^(1/3) = K^(1/3) delta^(1/2) and
  // refines it when damping has moved Q off Q_H, or falls back to std::cbrt.
  for (double K : {3.1e9, 8.7e9})
    for (double delta = 1e-9; delta < 1e-4; delta *= 3.1) {
      const double root = std::sqrt(delta), QH = K * delta * root, cbrt_QH = std::cbrt(K) * root;
      for (double ratio : {0.0, 0.5, 0.89, 0.9, 0.95, 0.999, 1.0, 1.0001, 1.05, 1.1, 1.11, 2.0}) {
        const double Q = ratio * QH;
        EXPECT_NEAR(ball_detail::load_cbrt(Q, QH, cbrt_QH), std::cbrt(Q), 1e-15 * std::cbrt(Q))
            << "delta " << delta << ", Q / Q_H " << ratio;
      }
    }
}

TEST(BallBearing, PocketGeometryIsTheCartesianOne) {
  // The pocket geometry from the angles' sines and cosines against the same construction in housing coordinates:
  // ball centre ((R_p + rho) cos psi, (R_p + rho) sin psi, zeta), pocket centre c + R_p (cos phi, sin phi, 0),
  // their difference turned into the ball's orbital basis. Small and large offsets of either sign, one beyond
  // a quarter turn (the cos < 0 branch), and angles of thousands of radians.
  const double Rp = 8.75e-3, rho = 3e-7, zeta = -2e-6;
  const Eigen::Vector3d c_h(4e-6, -7e-6, 1e-6);  // cage centre, housing frame
  for (double psi : {0.3, -2.1, 6283.4})
    for (double dpsi : {0.0, 1e-9, -1e-5, 0.0137, -0.02, 2.0, -3.1}) {
      const double phi = psi - dpsi;
      const double c = std::cos(psi), sn = std::sin(psi);
      double sd, cd;
      ball_detail::pocket_offset(c, sn, std::cos(phi), std::sin(phi), sd, cd);
      ball_detail::PocketGeometry g;
      ball_detail::pocket_geometry(rho, zeta, sd, cd, Rp, ball_detail::to_orbital(c_h.x(), c_h.y(), c_h.z(), c, sn), g);
      const Eigen::Vector3d ball((Rp + rho) * c, (Rp + rho) * sn, zeta);
      const Eigen::Vector3d pocket_h = Rp * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0);
      const Eigen::Vector3d d_h = ball - c_h - pocket_h;
      const Eigen::Vector3d d_o = ball_detail::to_orbital(d_h.x(), d_h.y(), d_h.z(), c, sn);
      const Eigen::Vector3d p_o = ball_detail::to_orbital(pocket_h.x(), pocket_h.y(), 0.0, c, sn);
      // Tolerance: the housing-frame construction subtracts two vectors of length R_p (round-off 2e-18 m) and
      // psi - dpsi near 6,283 rad rounds phi by up to 5e-13 rad (4e-15 m at R_p).
      const double tol = (psi > 100.0 ? 1e-14 : 1e-17);
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(g.delta_vec(i), d_o(i), tol) << "psi " << psi << ", dpsi " << dpsi << ", component " << i;
        EXPECT_NEAR(g.pocket(i), p_o(i), tol + 1e-15 * Rp) << "psi " << psi << ", dpsi " << dpsi;
      }
      EXPECT_NEAR(g.dist, d_h.norm(), tol);
    }
}

TEST(BallBearing, PocketContactsRepeatWithTheOrbitAngle) {
  // The pockets' geometry comes from the sines and cosines of the ball and cage angles (no reduction of their
  // difference): a thousand turns added to every ball and to the cage give the same forces to the precision the
  // angles carry (psi near 6,300 rad has an ulp of 9e-13 rad, 8 pm at the pitch circle, against a pocket
  // penetration of 20 um). Ball 2 pressed into its pocket from either side of the cage angle's zero.
  BallBearingSpec spec = reference_bearing();
  const BallBearingElement e("ref", spec, 0, 9.81);
  const double W = 60000 * kRpm;
  const SpinState s{0.0, W, 0.0, 0.0};
  for (double sign : {1.0, -1.0}) {
    std::vector<double> z(e.n_states()), zdot0(e.n_states()), zdot1(e.n_states());
    e.initial_states(z.data());
    e.steady_states(W, z.data());
    z[e.ball_offset(2) + 0] += sign * 1.2 * spec.pocket_clearance / (0.5 * spec.pitch_diameter);
    const double q[4] = {2e-6, -1e-6, 2e-5, -1e-5}, v[4] = {0.02, -0.01, 3.0, 2.0};
    BallBearingLoads loads0, loads1;
    e.calc_bearing(s, q, v, z.data(), OuterRingKinematics{}, loads0, zdot0.data());
    ASSERT_GT(loads0.friction_loss_pocket, 0.0);
    for (int j = 0; j < spec.n_balls; ++j) z[e.ball_offset(j)] += 2000.0 * M_PI;
    z[e.cage_offset() + 3] += 2000.0 * M_PI;
    e.calc_bearing(s, q, v, z.data(), OuterRingKinematics{}, loads1, zdot1.data());
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(loads1.shaft[i], loads0.shaft[i], 1e-6 * std::abs(loads0.shaft[i]) + 1e-9);
    EXPECT_NEAR(loads1.friction_loss_pocket, loads0.friction_loss_pocket, 1e-6 * loads0.friction_loss_pocket);
    for (int i = 0; i < e.n_states(); ++i)
      EXPECT_NEAR(zdot1[i], zdot0[i], 1e-6 * std::abs(zdot0[i]) + 1e-9) << "state " << i << ", sign " << sign;
  }
}

TEST(BallBearing, PartialEvaluationsRedoOnlyTheContactsTheyMoveAndEqualAFullOne) {
  // The Jacobian's shaft, cage and outer-ring columns evaluate only the inner-race, pocket or outer-race contacts
  // and take the others from the base state (calc_bearing with a BallContactCache). At a state where every kind of
  // contact carries load (ball 2 in its pocket, the rings off centre and moving), each such partial evaluation
  // after a change of its own inputs equals a full evaluation at the changed state to round-off; with the wrong
  // contacts redone it does not (the change would not be seen).
  BallBearingSpec spec = reference_bearing();
  const BallBearingElement e("ref", spec, 0, 9.81);
  const double W = 60000 * kRpm;
  const SpinState s{0.0, W, 0.0, 0.0};
  const int n = e.n_states();
  std::vector<double> z(n), zdot_full(n), zdot_part(n), zdot_base(n);
  e.initial_states(z.data());
  e.steady_states(W, z.data());
  z[e.ball_offset(2) + 0] += 1.2 * spec.pocket_clearance / (0.5 * spec.pitch_diameter);
  double q[4] = {2e-6, -1e-6, 2e-5, -1e-5}, v[4] = {0.02, -0.01, 3.0, 2.0};
  OuterRingKinematics outer{1e-6, -2e-6, 0.01, 0.02};
  BallContactCache cache;
  cache.parts.resize(3 * static_cast<std::size_t>(spec.n_balls));
  BallBearingLoads base, full, part;
  std::vector<BallShare> shares_full(spec.n_balls), shares_part(spec.n_balls);
  e.calc_bearing(s, q, v, z.data(), outer, base, zdot_base.data(), nullptr, &cache, kAllContacts);
  ASSERT_GT(base.friction_loss_pocket, 0.0);
  ASSERT_GT(base.friction_loss_inner, 0.0);
  ASSERT_GT(base.friction_loss_outer, 0.0);
  const auto compare = [&](const char* what, unsigned redo, bool equal) {
    e.calc_bearing(s, q, v, z.data(), outer, full, zdot_full.data(), shares_full.data());
    e.calc_bearing(s, q, v, z.data(), outer, part, zdot_part.data(), shares_part.data(), &cache, redo);
    double worst = 0.0;  // in the derivatives that the change moved, relative to how far it moved them
    double unmoved = 0.0;  // in the others, relative to their size
    for (int i = 0; i < n; ++i) {
      const double moved = std::abs(zdot_full[i] - zdot_base[i]), diff = std::abs(zdot_part[i] - zdot_full[i]);
      if (moved > 1e-9 * std::abs(zdot_full[i]))
        worst = std::max(worst, diff / moved);
      else if (diff > 0.0)
        unmoved = std::max(unmoved, diff / std::abs(zdot_full[i]));
    }
    for (int i = 0; i < 4; ++i) worst = std::max(worst, std::abs(part.shaft[i] - full.shaft[i]) / std::abs(full.shaft[i]));
    for (int i = 0; i < 3; ++i)
      worst = std::max(worst, std::abs(part.outer_ring[i] - full.outer_ring[i]) / std::abs(full.outer_ring[i]));
    if (!equal) {
      EXPECT_GT(worst, 1e-3) << what << ": the wrong contacts redone must show";
      return;
    }
    EXPECT_LT(worst, 1e-6) << what;  // of the change the inputs made, in every derivative that changed
    EXPECT_LT(unmoved, 1e-12) << what;  // the derivatives it did not change stay as they were
    for (int j = 0; j < spec.n_balls; ++j) {
      for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(shares_part[j].shaft[i], shares_full[j].shaft[i], 1e-12 * std::abs(full.shaft[i % 4]) + 1e-15);
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(shares_part[j].outer[i], shares_full[j].outer[i], 1e-12 * std::abs(full.outer_ring[i]) + 1e-15);
      for (int i = 0; i < 4; ++i) EXPECT_NEAR(shares_part[j].cage[i], shares_full[j].cage[i], 1e-12);
    }
  };
  q[0] += 1e-7;  // the shaft
  v[3] += 0.5;
  compare("shaft", kInnerContacts, true);
  compare("shaft, pockets redone", kPocketContacts, false);
  q[0] -= 1e-7;
  v[3] -= 0.5;
  z[e.cage_offset() + 3] += 1e-6;  // the cage
  z[e.cage_offset() + 4] += 1e-3;
  compare("cage", kPocketContacts, true);
  compare("cage, outer races redone", kOuterContacts, false);
  z[e.cage_offset() + 3] -= 1e-6;
  z[e.cage_offset() + 4] -= 1e-3;
  z[e.outer_offset()] += 1e-8;  // the outer ring, axially and radially
  outer.vx += 0.01;
  compare("outer ring", kOuterContacts, true);
  compare("outer ring, inner races redone", kInnerContacts, false);
}

TEST(BallBearing, PlanarTractionIgnoresSlipAcrossTheRollingDirection) {
  // race_traction = planar (the paper's planar contact) keeps only the slip along the rolling direction. An axial
  // velocity of every ball slips its race contacts across the rolling direction only: with planar traction the race
  // friction losses do not change, with spatial traction they grow. Spin friction and contact damping off, shaft
  // centred, so that only the slip counts.
  const double W = 30000 * kRpm;
  const SpinState s{0.0, W, 0.0, 0.0};
  const double q[4] = {0, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  const auto race_losses = [&](RaceTraction traction, double axial_velocity) {
    BallBearingSpec spec = reference_bearing();
    spec.spin_friction = false;
    spec.contact_damping = 0.0;  // the axial velocity must not change the normal forces
    spec.race_traction = traction;
    const BallBearingElement e("ref", spec, 0, 0.0);
    std::vector<double> z(e.n_states()), zdot(e.n_states());
    e.initial_states(z.data());
    e.steady_states(W, z.data());
    for (int j = 0; j < spec.n_balls; ++j) z[e.ball_offset(j) + 5] = axial_velocity;
    BallBearingLoads loads;
    e.calc_bearing(s, q, v, z.data(), OuterRingKinematics{}, loads, zdot.data());
    return loads.friction_loss_inner + loads.friction_loss_outer;
  };
  const double planar0 = race_losses(RaceTraction::Planar, 0.0), planar1 = race_losses(RaceTraction::Planar, 2e-3);
  const double spatial0 = race_losses(RaceTraction::Spatial, 0.0), spatial1 = race_losses(RaceTraction::Spatial, 2e-3);
  EXPECT_NEAR(planar1, planar0, 1e-9 * std::max(planar0, 1e-6));
  EXPECT_GT(spatial1 - spatial0, 1e-3) << spatial0 << " -> " << spatial1;
}

// The reference bearing's inner race contact (ball 4.5 mm, pitch 17.5 mm, groove 0.52, 15 deg, steel), the
// lubricated-traction tests' contact at 20 N and an entrainment speed of 20 m/s.
constexpr double kTractionLoad = 20.0, kTractionEntrainment = 20.0;
const double kSteelModulus = 2.0 / (2.0 * (1.0 - 0.3 * 0.3) / 208e9);  // E'
HertzPointContact reference_inner_contact() {
  double cx = 0.0, cy = 0.0;
  RaceCurvatures(4.5e-3, 17.5e-3, 0.52, 15.0 * 3.14159265358979323846 / 180.0, true, &cx, &cy);
  return SolveHertzPointContact(cx, cy, kSteelModulus);
}

TEST(BallBearing, LubricatedTractionHasItsViscousAndLimitingRanges) {
  // TractionLaw::Eyring at the reference bearing's inner contact, 20 N, entrainment 20 m/s, an engine oil of
  // 10 mPa s: against the closed forms of its two ends and the film thickness's speed exponent.
  constexpr double kQ = kTractionLoad, kU = kTractionEntrainment;
  const HertzPointContact hz = reference_inner_contact();
  const double modulus = kSteelModulus, cx = hz.curvature_x;
  const EyringLubricant lub{0.01, 2e-8, 5e6, 0.08};
  // Viscous end: F / v = eta(p) A / h, the same at any small slip.
  const double radius = hz.radius_factor * std::cbrt(kQ), area = M_PI * radius * radius, p = kQ / area;
  const double Rx = 1.0 / cx;
  const double h = Rx * 2.69 * std::pow(lub.viscosity * kU / (modulus * Rx), 0.67) *
                   std::pow(lub.pressure_viscosity * modulus, 0.53) * std::pow(kQ / (modulus * Rx * Rx), -0.067) *
                   (1.0 - 0.61 * std::exp(-0.73 * hz.ellipticity));
  const double viscous = lub.viscosity * std::exp(lub.pressure_viscosity * p) * area / h;
  EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 1e-12) / viscous, 1.0, 1e-9);
  EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 0.0) / viscous, 1.0, 1e-9);
  // Limiting end: F -> gamma p A = gamma Q (the Eyring stress grows only with log(slip), so far out).
  EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 1e30) * 1e30 / kQ, lub.limiting_shear, 1e-5);
  // h ~ u^0.67: at small slip F / v ~ 1 / h.
  EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, 0.5 * kU, 0.0) / viscous, std::pow(2.0, 0.67), 1e-9);
  // The force grows with the slip and stays below the limit.
  double last = 0.0;
  std::printf("[ eyring ] p %.3g GPa, h %.3g um; mu at slip", p * 1e-9, h * 1e6);
  for (double v : {1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0}) {
    const double force = eyring_traction_per_slip(lub, hz, kQ, kU, v) * v;
    EXPECT_GT(force, last);
    EXPECT_LT(force, lub.limiting_shear * kQ);
    last = force;
    std::printf(" %.0e m/s: %.4f;", v, force / kQ);
  }
  std::printf("\n");
  EXPECT_EQ(eyring_traction_per_slip(lub, hz, 0.0, kU, 1.0), 0.0);
}

TEST(BallBearing, LubricatedTractionWithAnElasticFilmHasTheMaxwellLimits) {
  // The film's shear modulus G (Johnson & Tevaarwerk's Maxwell term) at zero slip: a film that relaxes within the
  // transit 2b/u is the viscous one (G -> infinity, or a low pressure), one that does not carries the elastic mean
  // stress G (2b/u) v / (2 h), whatever its viscosity; in between the slope falls with G and the large-slip end is
  // still the limiting shear stress.
  constexpr double kQ = kTractionLoad, kU = kTractionEntrainment;
  const HertzPointContact hz = reference_inner_contact();
  ASSERT_GT(hz.ellipticity, 1.0);
  const double radius = hz.radius_factor * std::cbrt(kQ), area = M_PI * radius * radius;
  const double b = radius / std::sqrt(hz.ellipticity), transit = 2.0 * b / kU;  // along the rolling direction
  const EyringLubricant viscous{0.01, 2e-8, 5e6, 0.08};
  // Stiff film: the viscous law.
  EyringLubricant lub = viscous;
  lub.shear_modulus = 1e30;
  EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 0.0) / eyring_traction_per_slip(viscous, hz, kQ, kU, 0.0),
              1.0, 1e-9);
  // Glassy film (alpha p = 70 at 20 N: eta = 2.5e28 Pa s): the elastic mean stress, independent of eta.
  for (double G : {1e8, 1e9}) {
    lub.shear_modulus = G;
    for (double alpha : {7e-8, 1e-7}) {
      lub.pressure_viscosity = alpha;
      EyringLubricant plain = viscous;
      plain.pressure_viscosity = alpha;
      // The same film thickness for both (it depends on alpha through G = alpha E' only).
      const double h_a = eyring_traction_per_slip(plain, hz, kQ, kU, 0.0) /
                         (0.01 * std::exp(std::min(alpha * kQ / area, 300.0)));
      const double elastic = 0.5 * G * transit * h_a;  // (G t / 2) A / h
      EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 0.0) / elastic, 1.0, 1e-9) << G << " " << alpha;
      EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 1e-9) / elastic, 1.0, 1e-6) << G << " " << alpha;
    }
  }
  // The reference oil: a softer film, a smaller slope at zero slip, the same limit at large slip.
  lub = viscous;
  double last = eyring_traction_per_slip(viscous, hz, kQ, kU, 0.0);
  for (double G : {1e10, 1e9, 1e8}) {
    lub.shear_modulus = G;
    const double slope = eyring_traction_per_slip(lub, hz, kQ, kU, 0.0);
    EXPECT_LT(slope, last) << G;
    last = slope;
    EXPECT_NEAR(eyring_traction_per_slip(lub, hz, kQ, kU, 1e30) * 1e30 / kQ, lub.limiting_shear, 1e-5);
  }
  lub.shear_modulus = 1e9;
  std::printf("[ eyring, G 1 GPa ] transit %.3g us, eta_eff/eta %.3g; mu at slip", transit * 1e6,
              eyring_traction_per_slip(lub, hz, kQ, kU, 0.0) / eyring_traction_per_slip(viscous, hz, kQ, kU, 0.0));
  for (double v : {1e-4, 1e-3, 1e-2, 0.1, 1.0})
    std::printf(" %.0e m/s: %.4f;", v, eyring_traction_per_slip(lub, hz, kQ, kU, v) * v / kQ);
  std::printf("\n");
}

TEST(BallBearing, ScaledTolerancesOfTheBallAndCageVelocitiesFollowTheirContactFrequencies) {
  // A scaled absolute tolerance resolves 1 um of displacement to atol; a part ringing at w on its contacts then
  // has 1 um of displacement per w x 1 um of velocity. The balls' and the cage's velocity tolerances must not be
  // looser than that (they would let the integrator misplace the contacts), and they are what lets it step over
  // the 40-kHz ringing it does not need to resolve. Reference bearing at rest under its preload: each ball on its
  // two contacts, the cage on one pocket at 1 N.
  const BallBearingSpec s = reference_bearing();
  const BallBearingElement e("b", s, 0, 0.0);
  const BallBearingEquilibrium r = BallBearingQuasiStatic(e).solve(0.0, Eigen::Vector3d::Zero());
  const auto contact_stiffness = [](const HertzPointContact& c, double load) {
    return 1.5 * std::pow(c.stiffness, 2.0 / 3.0) * std::cbrt(load);  // dQ/d(delta) of Q = K delta^1.5
  };
  const QuasiStaticBall& b = r.balls.at(0);
  ASSERT_GT(b.inner_load, 1.0);
  const double k_ball = contact_stiffness(e.inner_contact(), b.inner_load) + contact_stiffness(e.outer_contact(),
                                                                                               b.outer_load);
  const double w_ball = std::sqrt(k_ball / e.ball_mass());
  const double w_cage = std::sqrt(1.5 * std::pow(e.pocket_stiffness(), 2.0 / 3.0) / s.cage_mass);
  std::printf("[ validation ] ball on its races %.1f kHz (1 um: %.3f m/s), cage on a pocket at 1 N %.1f kHz "
              "(%.3f m/s)\n", w_ball / 2e3 / M_PI, w_ball * 1e-6, w_cage / 2e3 / M_PI, w_cage * 1e-6);
  EXPECT_LE(BallBearingElement::kBallVelocityTolerance, w_ball * ForceElement::kTypicalDisplacement);
  EXPECT_LE(BallBearingElement::kCageVelocityTolerance, w_cage * ForceElement::kTypicalDisplacement);
  // Which states: a ball's radial and axial velocities and its spins (as surface speeds), the cage's velocities;
  // every other state keeps its typical magnitude.
  const int cage = BallBearingElement::kBallStates * s.n_balls;
  for (int i = 0; i < e.n_states(); ++i) {
    const int k = i < cage ? i % BallBearingElement::kBallStates : -1;
    double expected = e.state_scale(i);
    if (k == 4 || k == 5) expected = 0.1;
    if (k >= 6) expected = 0.1 / (0.5 * s.ball_diameter);
    if (i >= cage + 4 && i <= cage + 6) expected = 0.05;
    EXPECT_DOUBLE_EQ(e.tolerance_scale(i), expected) << "state " << i;
  }
}

TEST(BallBearing, BadSpecValuesThrowNamingTheField) {
  const auto expect_throw = [](void (*edit)(BallBearingSpec&), const std::string& field) {
    BallBearingSpec s;
    edit(s);
    try {
      BallBearingElement e("bad", s, 0, 9.81);
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& ex) {
      EXPECT_NE(std::string(ex.what()).find(field), std::string::npos) << ex.what();
    }
  };
  expect_throw([](BallBearingSpec& s) { s.ball_diameter = -1e-3; }, "ball_diameter");
  expect_throw([](BallBearingSpec& s) { s.inner_groove_ratio = 0.5; }, "inner_groove_ratio");
  expect_throw([](BallBearingSpec& s) { s.outer_groove_ratio = 0.4; }, "outer_groove_ratio");
  expect_throw([](BallBearingSpec& s) { s.n_balls = 2; }, "n_balls");
  expect_throw([](BallBearingSpec& s) { s.n_balls = 13; }, "n_balls");  // 13 x 4.5 mm > pi x 17.5 mm
  expect_throw([](BallBearingSpec& s) { s.pocket_clearance = 0.0; }, "pocket_clearance");
  expect_throw([](BallBearingSpec& s) { s.pitch_diameter = 4e-3; }, "pitch_diameter");
  expect_throw([](BallBearingSpec& s) { s.contact_angle = -0.1; }, "contact_angle");
  expect_throw([](BallBearingSpec& s) { s.side = 0; }, "side");
  expect_throw([](BallBearingSpec& s) { s.ball_density = 0.0; }, "ball_density");
  expect_throw([](BallBearingSpec& s) { s.ring_poisson_ratio = 0.5; }, "ring_poisson_ratio");
  expect_throw([](BallBearingSpec& s) { s.contact_damping = -1.0; }, "contact_damping");
  expect_throw([](BallBearingSpec& s) { s.friction_v2 = 0.0; }, "friction_v2");
  expect_throw([](BallBearingSpec& s) { s.preload = -40.0; }, "preload");
  expect_throw([](BallBearingSpec& s) { s.cage_mass = 0.0; }, "cage_mass");
  expect_throw(
      [](BallBearingSpec& s) {
        s.outer_ring_mode = OuterRingMode::Spring;
        s.outer_ring_stiffness = 0.0;
      },
      "outer_ring_stiffness");
  std::string error;
  EXPECT_TRUE(BallBearingSpec{}.IsValid(&error)) << error;
}

}  // namespace
}  // namespace turbodyn
