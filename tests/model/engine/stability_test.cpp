// The linearised stability analysis of the whole run-up model (model/engine/stability.h) on the reference rotor in
// ball bearings: its steady state against the quasi-static bearing model, its rotor modes against the quasi-static
// modal analysis where friction plays little part, and the friction-driven instability of issue 17.
#include "model/engine/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/io/model_file.h"
#include "model/io/overrides.h"
#include "model/rotor/modal.h"
#include "model/spec/constants.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

MachineSpec reference_ball() { return load_model(testing::source_dir() + "/examples/reference_ball.toml"); }

TEST(Stability, SteadyStateTurnsAtTheQuasiStaticCageSpeed) {
  // The Newton/pseudo-transient steady state of the element (friction, spin moments, contact damping) turns at the
  // cage speed of the quasi-static model (outer-race control, no friction but the gyroscopic traction), 100,000 rpm.
  // The element's own steady run agrees with the quasi-static orbit speed to 0.05 % (docs/ball-bearing.md); here
  // 0.3 % allows for the friction's slip.
  constexpr double kSpeed = 100000 * kRpmToRadPerS, kTolerance = 0.003;
  const MachineSpec spec = reference_ball();
  const StabilityPoint p = analyse_stability(spec, kSpeed);
  const BallBearingElement element("compressor", spec.bearings[0].ball, 0, 0.0);
  const BallBearingQuasiStatic qs(element);
  const std::vector<BallBearingEquilibrium> eq = qs.sweep({kSpeed}, Eigen::Vector3d::Zero());
  std::printf("[ steady ] cage %.2f rad/s (quasi-static %.2f), residual %.2e, %d states\n", p.frame_speed,
              eq.back().cage_speed, p.residual, p.n_states);
  EXPECT_NEAR(p.frame_speed / eq.back().cage_speed, 1.0, kTolerance);
  EXPECT_LT(p.residual, 1e-6);
  EXPECT_EQ(p.elements, (std::vector<std::string>{"compressor", "turbine"}));
}

TEST(Stability, ALubricatedBearingThatTheContinuationCannotStartIsFoundDirectlyAtSpeed) {
  // The lubricated traction (Eyring, the model file's default law) with 200 N of preload: its traction is so stiff at
  // the smallest entrainment speeds that not even the continuation's first step from rest (31 rpm) converges. The
  // steady state is then sought at the speed itself from the no-slip state; it is the rolling state: the cage turns
  // at the quasi-static cage speed (as in SteadyStateTurnsAtTheQuasiStaticCageSpeed, 0.3 % for the traction's slip).
  constexpr double kSpeed = 100000 * kRpmToRadPerS, kTolerance = 0.003;
  const MachineSpec spec = load_model(
      testing::source_dir() + "/examples/reference_ball.toml",
      {parse_override("bearings.compressor.traction_law=eyring"),
       parse_override("bearings.turbine.traction_law=eyring"), parse_override("bearings.compressor.preload=200 N"),
       parse_override("bearings.turbine.preload=200 N")});
  const StabilityPoint p = analyse_stability(spec, kSpeed);
  const BallBearingElement element("compressor", spec.bearings[0].ball, 0, 0.0);
  const BallBearingQuasiStatic qs(element);
  const std::vector<BallBearingEquilibrium> eq = qs.sweep({kSpeed}, Eigen::Vector3d::Zero());
  std::printf("[ eyring, 200 N ] cage %.2f rad/s (quasi-static %.2f), residual %.2e\n", p.frame_speed,
              eq.back().cage_speed, p.residual);
  EXPECT_NEAR(p.frame_speed / eq.back().cage_speed, 1.0, kTolerance);
  EXPECT_LT(p.residual, 1e-6);
}

TEST(Stability, OnIsotropicLinearBearingsTheModesAreTheModalAnalysisOnes) {
  // examples/reference_linear.toml (k = 3e7 N/m, c = 100 N s/m, no states, no turning frame) at 60,000 rpm: the
  // linearisation of the run-up model's right-hand side is the rotor's own linear model, so its eigenvalues are the
  // modal analysis', up to the central differences' round-off.
  constexpr double kSpeed = 60000 * kRpmToRadPerS, kTolerance = 1e-6;
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_linear.toml");
  const StabilityPoint p = analyse_stability(spec, kSpeed);
  EXPECT_EQ(p.frame_speed, 0.0);
  const ModalResult modal = modal_analysis(build_rotor(spec), kSpeed, ModalOptions{6});
  ASSERT_GE(modal.modes.size(), 6u);
  for (const Mode& m : modal.modes) {
    const double signed_modal = m.whirl == Whirl::Backward ? -m.frequency : m.frequency;
    double best = 1e30, zeta = 0.0;
    for (const StabilityMode& s : p.modes)
      if (std::abs(s.frequency - signed_modal) < std::abs(best - signed_modal)) best = s.frequency, zeta = s.damping_ratio;
    EXPECT_NEAR(best / signed_modal, 1.0, kTolerance) << signed_modal << " Hz";
    EXPECT_NEAR(zeta, m.damping_ratio, 1e-6) << signed_modal << " Hz";
  }
}

TEST(Stability, RotorModesAtLowSpeedAreTheModalAnalysisOnes) {
  // At 30,000 rpm the four lowest rotor modes (two backward, two forward) in the housing frame match `turbodyn
  // modal` with the quasi-static bearing stiffness. A wrong frame transformation would move them by the cage
  // frequency (190 Hz, 30 %). They are not equal: the race friction in its creep range ties the balls' tangential
  // motion to the races, which the quasi-static model (balls in their azimuth planes, no friction) leaves out;
  // measured +3 to +6 %, so 8 %.
  constexpr double kSpeed = 30000 * kRpmToRadPerS, kTolerance = 0.08;
  const MachineSpec spec = reference_ball();
  const StabilityPoint p = analyse_stability(spec, kSpeed);
  std::vector<double> full;  // signed housing-frame frequencies of the rotor modes below 1 kHz, ascending |f|
  for (const StabilityMode& m : p.modes)
    if (m.rotor_share > 0.5 && std::abs(m.frequency) < 1000.0) {
      full.push_back(m.frequency);
      EXPECT_LT(m.growth_rate, 0.0) << m.frequency << " Hz";
    }
  std::sort(full.begin(), full.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  Rotor rotor = build_rotor(spec);
  add_ball_bearing_linearisations(spec, rotor);
  const ModalResult modal = modal_analysis(rotor, kSpeed, ModalOptions{4});
  ASSERT_EQ(full.size(), 4u);
  ASSERT_GE(modal.modes.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const Mode& m = modal.modes[static_cast<std::size_t>(i)];
    const double signed_modal = m.whirl == Whirl::Backward ? -m.frequency : m.frequency;
    std::printf("[ 30,000 rpm ] mode %d: %.1f Hz (modal %.1f Hz)\n", i + 1, full[static_cast<std::size_t>(i)],
                signed_modal);
    EXPECT_NEAR(full[static_cast<std::size_t>(i)] / signed_modal, 1.0, kTolerance) << "mode " << i + 1;
  }
}

TEST(Stability, RaceFrictionDestabilisesAForwardWhirlAboveSixtyThousandRpm) {
  // Issue 17: at 30,000 rpm every mode with rotor motion (rotor share >= 1 %) is stable, at 95,000 rpm a forward
  // whirl near the cage frequency grows (the ball set's one-lobed density wave with the rotor; docs/ball-bearing.md,
  // "Linearised stability").
  constexpr double kRotorMotion = 0.01;
  const MachineSpec spec = reference_ball();
  const StabilityPoint low = analyse_stability(spec, 30000 * kRpmToRadPerS);
  for (const StabilityMode& m : low.modes) {
    if (m.grows())
      std::printf("[ 30,000 rpm ] growing: %.1f Hz, zeta %.3g, rotor share %.2e\n", m.frequency, m.damping_ratio,
                  m.rotor_share);
    if (m.rotor_share >= kRotorMotion) {
      EXPECT_FALSE(m.grows()) << m.frequency << " Hz";
    }
  }
  const StabilityPoint high = analyse_stability(spec, 95000 * kRpmToRadPerS);
  ASSERT_FALSE(high.modes.empty());
  const StabilityMode& top = high.modes.front();
  const double cage_hz = high.frame_speed / (2.0 * kPi);
  std::printf("[ 95,000 rpm ] %.1f Hz, growth %.1f 1/s, zeta %.3g, rotor share %.3f (cage %.1f Hz)\n", top.frequency,
              top.growth_rate, top.damping_ratio, top.rotor_share, cage_hz);
  EXPECT_LT(top.damping_ratio, -1e-2);
  EXPECT_GT(top.frequency, 0.0);
  EXPECT_NEAR(top.frequency / cage_hz, 1.0, 0.2);
  // It is the ball set's one-lobed density wave (docs/ball-bearing.md: 76 % of the scaled mode in the balls'
  // orbital angles, the phase turning by -45 degrees from ball to ball); the rotor modes at 30,000 rpm have no
  // ball-set order.
  std::printf("[ 95,000 rpm ] ball-set share %.3f, lobes %d\n", top.ball_set_share, top.ball_set_lobes);
  EXPECT_GT(top.ball_set_share, 0.5);
  EXPECT_EQ(top.ball_set_lobes, 1);
  for (const StabilityMode& m : low.modes)
    if (m.rotor_share > 0.5) {
      EXPECT_EQ(m.ball_set_lobes, -1) << m.frequency << " Hz, ball-set share " << m.ball_set_share;
    }
}

TEST(Stability, TheBallSetsWaveGrowsOnlyWhereTheShaftCanMoveAtTheBearings) {
  // The loop of the instability (docs/ball-bearing.md, "Linearised stability"): the one-lobed wave puts the ball
  // set's mass centre off the axis, its centrifugal force moves the shaft in its bearings, the moved shaft changes
  // the balls' rolling speeds around the races and so the wave. Springs of 1e11 N/m from each bearing's shaft node
  // to the housing (10^4 x the bearings' own stiffness at speed, tilt left free) break that loop: at 60,000 rpm the
  // largest growth rate falls from 118 1/s to 2.5 1/s (measured), so below a tenth of the free shaft's.
  constexpr double kSpeed = 60000 * kRpmToRadPerS, kHold = 1e11;
  const MachineSpec free = reference_ball();
  MachineSpec held = free;
  for (const BearingSpec& ball : free.bearings) {
    BearingSpec hold;
    hold.name = ball.name + "_hold";
    hold.type = BearingType::Linear;
    hold.z = ball.z;
    hold.linear.k = {std::vector<double>{kHold}, {0.0}, {0.0}, {kHold}};
    hold.linear.c = {std::vector<double>{0.0}, {0.0}, {0.0}, {0.0}};
    held.bearings.push_back(hold);
  }
  const StabilityPoint p_free = analyse_stability(free, kSpeed), p_held = analyse_stability(held, kSpeed);
  ASSERT_FALSE(p_free.modes.empty());
  ASSERT_FALSE(p_held.modes.empty());
  const StabilityMode &f = p_free.modes.front(), &h = p_held.modes.front();
  std::printf("[ 60,000 rpm ] free shaft %.1f Hz %.1f 1/s (lobes %d), held shaft %.1f Hz %.2f 1/s (lobes %d)\n",
              f.frequency, f.growth_rate, f.ball_set_lobes, h.frequency, h.growth_rate, h.ball_set_lobes);
  EXPECT_EQ(f.ball_set_lobes, 1);
  EXPECT_GT(f.growth_rate, 50.0);
  EXPECT_LT(h.growth_rate, 0.1 * f.growth_rate);
  EXPECT_NEAR(p_held.frame_speed / p_free.frame_speed, 1.0, 1e-6);
}

TEST(Stability, TheContinuationHalvesAStepThatFindsNoSteadyState) {
  // With 200 N of preload the continuation's second regular step towards 20,000 rpm (2,222 -> 4,444 rpm) found no
  // steady state, while the same speeds reached in other steps did; a failing step is now retried at half the
  // length. The regular steps are unchanged: the example's state at 95,000 rpm is the one before (the other tests).
  MachineSpec spec = reference_ball();
  for (BearingSpec& b : spec.bearings) b.ball.preload = 200.0;
  const StabilityPoint p = analyse_stability(spec, 20000 * kRpmToRadPerS);
  EXPECT_LT(p.residual, 1e-6);
  ASSERT_FALSE(p.modes.empty());
  EXPECT_NEAR(p.frame_speed / (20000 * kRpmToRadPerS), 0.378, 0.01);  // the cage speed ratio at 200 N
}

TEST(Stability, TheWhirlIsTheBearingsOwnAndRoundOffAtHighFrequencyIsDropped) {
  // A shaft 430 times stiffer (E = 9e13 Pa): the growing whirl near the cage frequency stays (docs/ball-bearing.md:
  // 630 Hz, 307 1/s at 95,000 rpm), so it is the bearings' own; the stiff shaft's bending modes at MHz, whose damping
  // ratios are round-off of -1e-5 to -6e-5, are not reported.
  constexpr double kSpeed = 95000 * kRpmToRadPerS, kFrequencyMax = 4.0 * kSpeed / (2.0 * kPi);
  MachineSpec spec = reference_ball();
  for (auto& [name, m] : spec.materials) {
    m.youngs_modulus = 9e13;
    m.shear_modulus = 9e13 / (2.0 * (1.0 + m.poisson_ratio));
  }
  const StabilityPoint p = analyse_stability(spec, kSpeed);
  ASSERT_FALSE(p.modes.empty());
  EXPECT_TRUE(p.modes.front().grows());
  EXPECT_NEAR(p.modes.front().frequency / (p.frame_speed / (2.0 * kPi)), 1.0, 0.05);
  for (const StabilityMode& m : p.modes)
    if (std::abs(m.frequency) > kFrequencyMax) {
      EXPECT_LT(m.damping_ratio, -1e-3) << m.frequency << " Hz";
    }
}

TEST(Stability, BallBearingsInADamperWhoseFilmIsTheSameInEveryDirection) {
  // examples/reference_ball_sfd.toml without its feed hole and supply pressure: the damper rings rest at the
  // centre, so the balls and cages turn as in the fixed-ring bearing (the same cage speed to round-off); the
  // example itself (a feed hole at the top, 4 bar) has no steady turning state and is refused.
  constexpr double kSpeed = 60000 * kRpmToRadPerS;
  MachineSpec sfd = load_model(testing::source_dir() + "/examples/reference_ball_sfd.toml");
  EXPECT_THROW(analyse_stability(sfd, kSpeed), std::invalid_argument);
  for (BearingSpec& b : sfd.bearings) {
    b.damper.feed_hole_diameter = 0.0;
    b.damper.supply_pressure = 0.0;
  }
  const StabilityPoint damped = analyse_stability(sfd, kSpeed);
  const StabilityPoint fixed = analyse_stability(reference_ball(), kSpeed);
  EXPECT_NEAR(damped.frame_speed / fixed.frame_speed, 1.0, 1e-9);
  EXPECT_EQ(damped.n_states, fixed.n_states + 8);  // each damper ring's x, y, vx, vy
  for (const StabilityMode& m : damped.modes)
    if (std::abs(m.frequency) < 1e-3) {
      EXPECT_FALSE(m.grows()) << "the rings' neutral place at 0 Hz counts as growing";
    }
  // Fed at its 4 bar through a central groove instead of the hole, the film is the same all round again: the
  // rings rest at the centre and the balls turn as before, on a film the supply keeps whole.
  for (BearingSpec& b : sfd.bearings) {
    b.damper.feed_groove_width = 1e-3;
    b.damper.supply_pressure = 4e5;
  }
  const StabilityPoint grooved = analyse_stability(sfd, kSpeed);
  EXPECT_NEAR(grooved.frame_speed / fixed.frame_speed, 1.0, 1e-9);
  EXPECT_EQ(grooved.n_states, damped.n_states);
}

TEST(Stability, AnAnalysisContinuedFromALowerSpeedIsTheOneFromRest) {
  // A sweep passes each analysis to the next: the steady state continued up from 45,000 rpm is the one the
  // continuation from rest reaches at 60,000 rpm, and so are its modes (frequencies to 1e-6, growth rates to a tenth
  // of what the analysis counts as round-off, a damping ratio of 1e-6). A point of another machine is refused.
  const MachineSpec spec = reference_ball();
  const StabilityPoint low = analyse_stability(spec, 45000 * kRpmToRadPerS);
  const StabilityPoint rest = analyse_stability(spec, 60000 * kRpmToRadPerS),
                       continued = analyse_stability(spec, 60000 * kRpmToRadPerS, {}, &low);
  EXPECT_NEAR(continued.frame_speed / rest.frame_speed, 1.0, 1e-9);
  EXPECT_LT(continued.residual, 1e-6);
  std::vector<const StabilityMode*> a, b;
  for (const StabilityMode& m : rest.modes)
    if (m.rotor_share >= 0.01) a.push_back(&m);
  for (const StabilityMode& m : continued.modes)
    if (m.rotor_share >= 0.01) b.push_back(&m);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 4u);
  const auto by_frequency = [](const StabilityMode* x, const StabilityMode* y) {
    return x->frequency < y->frequency;
  };
  std::sort(a.begin(), a.end(), by_frequency);
  std::sort(b.begin(), b.end(), by_frequency);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(b[k]->frequency, a[k]->frequency, 1e-6 * std::abs(a[k]->frequency)) << "mode " << k;
    const double round_off = 0.1 * kStabilityNoiseDamping * 2.0 * kPi * std::abs(a[k]->frequency);
    EXPECT_NEAR(b[k]->growth_rate, a[k]->growth_rate, round_off) << "mode " << k;
    EXPECT_EQ(b[k]->grows(), a[k]->grows()) << "mode " << k;
  }
  EXPECT_FALSE(continued.restarted);
  EXPECT_FALSE(rest.restarted);
  // A state below that cannot be continued (here spoilt on purpose) is left: the state is found anew from rest, the
  // same as `rest`, and marked.
  StabilityPoint spoilt = low;
  std::fill(spoilt.steady_state.begin(), spoilt.steady_state.end(), std::numeric_limits<double>::quiet_NaN());
  const StabilityPoint anew = analyse_stability(spec, 60000 * kRpmToRadPerS, {}, &spoilt);
  EXPECT_TRUE(anew.restarted);
  EXPECT_EQ(anew.frame_speed, rest.frame_speed);
  EXPECT_EQ(anew.modes.size(), rest.modes.size());
  const StabilityPoint other = analyse_stability(load_model(testing::source_dir() + "/tests/data/stability/"
                                                            "rigid_cross_coupled.toml"),
                                                 10000 * kRpmToRadPerS);
  EXPECT_THROW(analyse_stability(spec, 60000 * kRpmToRadPerS, {}, &other), std::logic_error);
  EXPECT_THROW(analyse_stability(spec, 30000 * kRpmToRadPerS, {}, &low), std::logic_error);  // not below
}

TEST(Stability, TheOnsetsHalvingsSayWhichFoundTheirSteadyStateAnewFromRest) {
  // The example's onset lies near 54,000 rpm. Halving 45,000-60,000 rpm from a stable analysis continues each
  // halving from the highest speed found stable: none starts anew. From a stable point that cannot be continued
  // (spoilt on purpose) the first halving, 52,500 rpm (stable), is found from rest and says so; the later ones
  // continue from it, and the onset is the same.
  const MachineSpec spec = reference_ball();
  const StabilityModeFilter filter{0.01, 0.0};
  const StabilityPoint stable = analyse_stability(spec, 45000 * kRpmToRadPerS);
  ASSERT_FALSE(grows_counted(stable, filter));
  std::string error;
  std::vector<double> restarted;
  const double onset = refine_stability_onset(spec, stable, 60000 * kRpmToRadPerS, filter, &error, &restarted);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(restarted.empty());
  EXPECT_GT(onset, 52500 * kRpmToRadPerS);
  EXPECT_LT(onset, 56000 * kRpmToRadPerS);
  StabilityPoint spoilt = stable;
  std::fill(spoilt.steady_state.begin(), spoilt.steady_state.end(), std::numeric_limits<double>::quiet_NaN());
  const double again = refine_stability_onset(spec, spoilt, 60000 * kRpmToRadPerS, filter, &error, &restarted);
  EXPECT_TRUE(error.empty()) << error;
  ASSERT_EQ(restarted.size(), 1u);
  EXPECT_DOUBLE_EQ(restarted[0], 52500 * kRpmToRadPerS);
  EXPECT_DOUBLE_EQ(again, onset);
}

TEST(Stability, WithThePapersFrictionTheSteadyStateDoesNotDependOnTheContinuationsSteps) {
  // Design 27 of the Eq. 23 variant of examples/study_reference_ball_stability_global.toml (271 N, 8.6 deg; docs/
  // studies.md). Eq. 23 saturates over a creep range of millimetres per second and has steady states close together:
  // with the regular steps (250 rad/s, 125 from rest) the continuation reached at 10,000 rpm a state in which the
  // balls' slip diverges at about 5,300 1/s, with half of them and a quarter the state without it. So the ball
  // bearing with Eq. 23 takes half the regular steps: the state is then that of a quarter of them.
  const MachineSpec spec = load_model(
      testing::source_dir() + "/examples/reference_ball.toml",
      {parse_override("bearings.compressor.preload=270.609 N"), parse_override("bearings.turbine.preload=270.609 N"),
       parse_override("bearings.compressor.contact_angle=8.64512 deg"),
       parse_override("bearings.turbine.contact_angle=8.64512 deg"),
       parse_override("bearings.compressor.pocket_clearance=0.0987157 mm"),
       parse_override("bearings.turbine.pocket_clearance=0.0987157 mm"),
       parse_override("bearings.compressor.cage_mass=2.39613 g"),
       parse_override("bearings.turbine.cage_mass=2.39613 g"),
       parse_override("bearings.compressor.ball_density=4794.04 kg/m^3"),
       parse_override("bearings.turbine.ball_density=4794.04 kg/m^3"),
       parse_override("bearings.compressor.inner_groove_ratio=0.506359"),
       parse_override("bearings.turbine.inner_groove_ratio=0.506359"),
       parse_override("bearings.compressor.outer_groove_ratio=0.525524"),
       parse_override("bearings.turbine.outer_groove_ratio=0.525524"),
       parse_override("bearings.compressor.contact_damping=436.454 N*s/m"),
       parse_override("bearings.turbine.contact_damping=436.454 N*s/m")});
  StabilityOptions half, twice;
  half.continuation_step_factor = 0.5;
  twice.continuation_step_factor = 2.0;  // the regular steps
  const double speed = 10000 * kRpmToRadPerS;
  const StabilityPoint p = analyse_stability(spec, speed), q = analyse_stability(spec, speed, half),
                       r = analyse_stability(spec, speed, twice);
  const auto top = [](const StabilityPoint& x) { return x.modes.empty() ? 0.0 : x.modes.front().growth_rate; };
  std::printf("[ design 27, Eq. 23, 10,000 rpm ] cage ratio %.6f (half the steps %.6f, twice %.6f); largest growth "
              "rate %.1f 1/s (%.1f, %.1f)\n",
              p.frame_speed / p.speed, q.frame_speed / q.speed, r.frame_speed / r.speed, top(p), top(q), top(r));
  EXPECT_NEAR(p.frame_speed / q.frame_speed, 1.0, 1e-6);
  EXPECT_NEAR(top(p), top(q), 1.0);
  EXPECT_LT(top(p), 100.0);  // no divergence of the balls' slip
  EXPECT_THROW(analyse_stability(spec, 10000 * kRpmToRadPerS, StabilityOptions{0.0, 0.0, 0.0}), std::logic_error);
}

TEST(Stability, EachSpeedAndASweepFindTheBranchOfTheRollingStateARunTakes) {
  // At 220 N of preload and 25 deg the steady rolling state has two branches from low speeds on (the balls' spin
  // axes near outer-race control or steeper; docs/ball-bearing.md, "A sweep over speeds"). A run-up of the paper's
  // ramp turns its cages at 0.389-0.393 of the rotor speed at 40,000-60,000 rpm, on the branch with 0.3910 at 50,000
  // rpm; the other has 0.3809 there. With steps of 250 rad/s from rest each speed's own continuation settled on the
  // other from 40,000 rpm on (0.3843 at 40,000 rpm, 0.3809 at 50,000 rpm) and landed on either by the accident of
  // its steps (0.381, 0.391, 0.381, 0.392 at 50,000-53,000 rpm). Now a sweep from 10,000 rpm that passes each
  // analysis to the next and each speed on its own from rest find the same state, the run's.
  const MachineSpec spec = load_model(
      testing::source_dir() + "/examples/reference_ball.toml",
      {parse_override("bearings.compressor.preload=220 N"), parse_override("bearings.turbine.preload=220 N"),
       parse_override("bearings.compressor.contact_angle=25 deg"),
       parse_override("bearings.turbine.contact_angle=25 deg")});
  const auto ratio = [](const StabilityPoint& p) { return p.frame_speed / p.speed; };
  std::vector<StabilityPoint> sweep;
  for (const double rpm : {10000.0, 20000.0, 30000.0, 40000.0, 50000.0})
    sweep.push_back(analyse_stability(spec, rpm * kRpmToRadPerS, {}, sweep.empty() ? nullptr : &sweep.back()));
  for (std::size_t k = 3; k < sweep.size(); ++k) {
    const StabilityPoint alone = analyse_stability(spec, sweep[k].speed);
    std::printf("[ branch ] %.0f rpm: cage / rotor speed %.5f in the sweep, %.5f on its own\n",
                sweep[k].speed / kRpmToRadPerS, ratio(sweep[k]), ratio(alone));
    EXPECT_NEAR(ratio(alone), ratio(sweep[k]), 1e-6) << sweep[k].speed / kRpmToRadPerS << " rpm";
  }
  EXPECT_NEAR(ratio(sweep[3]), 0.3886, 0.0005);  // 40,000 rpm; the other branch 0.3843
  EXPECT_NEAR(ratio(sweep[4]), 0.3910, 0.0005);  // 50,000 rpm; the other branch 0.3809
  for (std::size_t k = 1; k < sweep.size(); ++k) EXPECT_GT(ratio(sweep[k]), ratio(sweep[k - 1]));
}

TEST(Stability, ElementsWithoutASteadyTurningStateAreRefused) {
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_floating_ring.toml");
  try {
    analyse_stability(spec, 50000 * kRpmToRadPerS);
    ADD_FAILURE() << "no error for floating rings";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bearing '"), std::string::npos) << e.what();
  }
  EXPECT_THROW(analyse_stability(reference_ball(), -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace turbodyn
