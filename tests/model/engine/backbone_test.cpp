// Critical speeds at an amplitude (model/engine/backbone.h): the synchronous whirl of the rotor on its ball
// bearings' quasi-static reaction, against the linear modal analysis on linear bearings (no amplitude dependence)
// and on the ball bearings' linearisation (small amplitudes), and against variant II's full run at its strong
// resonance (large amplitudes).
#include "model/engine/backbone.h"

#include <cmath>
#include <cstdio>
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
#include "tests/model/engine/rigid_ball_rotor.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// The forward 1x critical speeds of `rotor` below `top` (rad/s) by the Campbell diagram (complex modes).
std::vector<double> forward_criticals(const Rotor& rotor, double top) {
  std::vector<double> speeds;
  for (int i = 0; i <= 12; ++i) speeds.push_back(top * i / 12.0);
  const Campbell c = campbell_diagram(rotor, speeds, {1.0}, ModalOptions{8});
  std::vector<double> out;
  for (const CriticalSpeed& cs : c.critical)
    if (cs.whirl == Whirl::Forward && cs.order == 1.0) out.push_back(cs.speed);
  return out;
}

TEST(Backbone, OnLinearBearingsItIsTheCampbellCriticalAtEveryAmplitude) {
  // examples/reference_linear.toml without its bearing damping: the synchronous whirl of a linear rotor has the same
  // speed at every amplitude, the undamped 1x forward critical speed of the complex eigenproblem (a different
  // computation: inertial frame, first-order form, bisection on the order line).
  const MachineSpec spec =
      load_model(testing::source_dir() + "/examples/reference_linear.toml",
                 {parse_override("bearings.compressor.c=0"), parse_override("bearings.turbine.c=0")});
  const Rotor rotor = build_rotor(spec);
  const std::vector<double> crit = forward_criticals(rotor, 150000 * kRpmToRadPerS);
  ASSERT_FALSE(crit.empty());
  BackboneOptions o;
  o.reference_nodes = {rotor.node_at(spec.disks.front().z)};
  o.amplitudes = {1e-6, 1e-4, 1e-2};
  const std::vector<Backbone> bbs = synchronous_backbones(spec, rotor, crit, o);
  ASSERT_EQ(bbs.size(), crit.size());
  for (const Backbone& b : bbs) {
    EXPECT_TRUE(b.stopped.empty()) << b.stopped;
    ASSERT_EQ(b.points.size(), 3u);
    for (const BackbonePoint& p : b.points) {
      EXPECT_NEAR(p.speed / b.linear_speed, 1.0, 1e-6) << "branch " << b.branch << " at " << p.amplitude;
      EXPECT_TRUE(p.bearings.empty());
    }
    std::printf("[ linear ] branch %d: %.1f rpm\n", b.branch + 1, b.points.back().speed / kRpmToRadPerS);
  }
}

TEST(Backbone, BallBearingsStartAtTheModalCriticalsAndMeetTheRunsResonanceAtItsAmplitude) {
  // examples/reference_ball.toml. Small whirls: the linearised rotor's critical speeds (`turbodyn modal`, 548.3 and
  // 700.1 Hz) to 1e-4. Large ones: variant II's full run (Eq. 23, docs/validation.md "Variant II", 2026-12-06 build)
  // passes its second forward critical with a forward synchronous whirl of the compressor wheel of 518.4 um at
  // 46,532 rpm (775.5 Hz, 5-ms windows), the bearings' synchronous forces then 2,880 N (compressor) and 1,462 N
  // (turbine). The undamped whirl of that amplitude has the run's bearing forces to 3 % and its speed within 2 %
  // below the run's (a passage on a ramp peaks a little after the backbone: 1.7 %).
  constexpr double kRunAmplitude = 518.4e-6, kRunSpeed = 46532 * kRpmToRadPerS;
  constexpr double kRunForceCompressor = 2880.0, kRunForceTurbine = 1462.0;
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  Rotor lin = build_rotor(spec);
  add_ball_bearing_linearisations(spec, lin);
  const std::vector<double> crit = forward_criticals(lin, 60000 * kRpmToRadPerS);
  ASSERT_EQ(crit.size(), 2u);
  const Rotor rotor = build_rotor(spec);
  ASSERT_TRUE(rotor.bearings.empty());
  BackboneOptions o;
  // The first mode moves the turbine end (the compressor wheel sits near its node), the second the compressor end.
  o.reference_nodes = {rotor.node_at(0.122)};
  o.amplitudes = {1e-8, 31e-6};
  const Backbone first = synchronous_backbones(spec, rotor, {crit[0]}, o).at(0);
  o.reference_nodes = {rotor.node_at(0.012)};
  o.amplitudes = {1e-8, 100e-6, kRunAmplitude};
  const Backbone second = synchronous_backbones(spec, rotor, {crit[1]}, o).at(0);
  ASSERT_TRUE(first.stopped.empty()) << first.stopped;
  ASSERT_TRUE(second.stopped.empty()) << second.stopped;
  // Given both wheels, each branch takes the one that moves most in its mode: the same backbones.
  o.reference_nodes = {rotor.node_at(0.012), rotor.node_at(0.122)};
  o.amplitudes = {31e-6};
  const std::vector<Backbone> both = synchronous_backbones(spec, rotor, crit, o);
  EXPECT_EQ(both.at(0).reference_node, rotor.node_at(0.122));
  EXPECT_EQ(both.at(1).reference_node, rotor.node_at(0.012));
  EXPECT_NEAR(both.at(0).points.at(0).speed / first.points[1].speed, 1.0, 1e-6);
  EXPECT_NEAR(first.points[0].speed / crit[0], 1.0, 1e-4);
  EXPECT_NEAR(second.points[0].speed / crit[1], 1.0, 1e-4);
  // The first critical softens (the preload's far-side contacts unload, the tilt stiffness saturates), the second
  // first softens and then hardens with the Hertz contacts.
  EXPECT_LT(first.points[1].speed, 0.95 * crit[0]);
  EXPECT_LT(second.points[1].speed, crit[1]);
  const BackbonePoint& big = second.points[2];
  EXPECT_GT(big.speed, crit[1]);
  ASSERT_EQ(big.bearings.size(), 2u);
  EXPECT_NEAR(std::abs(big.bearings[0].force) / kRunForceCompressor, 1.0, 0.03);
  EXPECT_NEAR(std::abs(big.bearings[1].force) / kRunForceTurbine, 1.0, 0.03);
  EXPECT_LT(big.speed, kRunSpeed);
  EXPECT_GT(big.speed, 0.98 * kRunSpeed);
  std::printf("[ ball ] first %.1f -> %.1f Hz at 31 um (turbine wheel); second %.1f -> %.1f Hz at 518.4 um, "
              "bearings %.0f / %.0f N (run: 775.5 Hz, 2880 / 1462 N)\n",
              crit[0] / (2 * M_PI), first.points[1].speed / (2 * M_PI), crit[1] / (2 * M_PI),
              big.speed / (2 * M_PI), std::abs(big.bearings[0].force), std::abs(big.bearings[1].force));
}

TEST(Backbone, ARigidSymmetricRotorWhirlsAtItsBearingsSecantStiffness) {
  // Closed form: a rigid rotor, symmetric about its middle (equal wheels, mirrored bearings), whirls in its
  // cylindrical mode without tilt, so its critical speed at a whirl radius A is Omega^2 = 2 F(A, Omega) / (m A),
  // F the radial load that holds one bearing's ring at A with its tilt held (the load-deflection curve, another
  // driver of the quasi-static model) and m the rotor's mass; solved here by fixed-point iteration in Omega. A
  // shaft of 14 mm and 1e14 Pa (476 times steel's modulus) leaves the bending at the 1e-3 level (-0.1 % at 30 um).
  const MachineSpec spec = testing::rigid_symmetric_ball_rotor();
  const BallBearingElement element("compressor", spec.bearings.at(0).ball, 0, 0.0);
  const BallBearingQuasiStatic qs(element);
  const Rotor rotor = build_rotor(spec);
  const double m = rotor.total_mass;
  auto closed_form = [&](double a) {
    double w = 3000.0;
    for (int it = 0; it < 30; ++it) w = std::sqrt(2.0 * qs.load_deflection(w, {a}).back().secant / m);
    return w;
  };
  Rotor lin = build_rotor(spec);
  add_ball_bearing_linearisations(spec, lin);
  const double w0 = std::sqrt(2.0 * qs.load_deflection(3000.0, {0.0}).back().tangent / m);
  double start = 0.0;  // the forward 1x critical nearest the cylindrical mode's
  for (double c : forward_criticals(lin, 150000 * kRpmToRadPerS))
    if (std::abs(c - w0) < std::abs(start - w0)) start = c;
  BackboneOptions o;
  o.reference_nodes = {rotor.node_at(0.035)};
  o.amplitudes = {1e-6, 10e-6, 30e-6};
  const Backbone b = synchronous_backbones(spec, rotor, {start}, o).at(0);
  ASSERT_TRUE(b.stopped.empty()) << b.stopped;
  for (const BackbonePoint& p : b.points) {
    const double expected = closed_form(p.amplitude);
    EXPECT_NEAR(p.speed / expected, 1.0, 2e-3) << "at " << p.amplitude * 1e6 << " um";
    EXPECT_NEAR(p.bearings[0].displacement / p.amplitude, 1.0, 2e-3);  // a rigid translation
    std::printf("[ rigid ] %5.1f um: %.2f Hz (closed form %.2f Hz)\n", p.amplitude * 1e6, p.speed / (2 * M_PI),
                expected / (2 * M_PI));
  }
}

TEST(Backbone, RefusesWhatItCannotTake) {
  const MachineSpec ball = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  const Rotor rotor = build_rotor(ball);
  BackboneOptions o;
  o.reference_nodes = {0};
  o.amplitudes = {2e-6, 1e-6};
  EXPECT_THROW(synchronous_backbones(ball, rotor, {3000.0}, o), std::invalid_argument);
  o.amplitudes = {0.0};
  EXPECT_THROW(synchronous_backbones(ball, rotor, {3000.0}, o), std::invalid_argument);
  const MachineSpec sfd = load_model(testing::source_dir() + "/examples/reference_ball_sfd.toml");
  o.amplitudes = {1e-6};
  try {
    synchronous_backbones(sfd, build_rotor(sfd), {3000.0}, o);
    ADD_FAILURE() << "a ball bearing in a damper accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("squeeze-film damper"), std::string::npos) << e.what();
  }
  MachineSpec cross = load_model(testing::source_dir() + "/examples/reference_linear.toml");
  cross.bearings.at(0).linear.k[1] = {1e6};  // kxy
  cross.bearings.at(0).linear.k[2] = {-1e6};  // kyx
  try {
    synchronous_backbones(cross, build_rotor(cross), {3000.0}, o);
    ADD_FAILURE() << "a cross-coupled bearing accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not cross-coupled"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace turbodyn
