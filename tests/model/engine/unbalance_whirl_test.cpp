// Nonlinear unbalance response (model/engine/unbalance_whirl.h): the synchronous whirl under the wheels' unbalance
// in the turning frame, against the linear response in the inertial frame (linear bearings, and ball bearings at a
// small unbalance), against a rigid rotor's closed form, and against variant II's run-ups through its first
// forward critical.
#include "model/engine/unbalance_whirl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_bearing_quasistatic.h"
#include "model/io/model_file.h"
#include "model/io/overrides.h"
#include "model/rotor/response.h"
#include "model/spec/constants.h"
#include "tests/model/engine/rigid_ball_rotor.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// Every point of every piece against the linear response at its speed: wheel radii (the major semi-axis of the
// circular orbit) and phases, bearing forces.
void expect_linear_response(const UnbalanceWhirl& nl, const Rotor& lin, double tolerance, double* worst) {
  for (const UnbalanceWhirlPiece& piece : nl.pieces)
    for (const UnbalanceWhirlPoint& p : piece.points) {
      const SteadyResponse r = unbalance_response(lin, p.speed);
      for (std::size_t d = 0; d < lin.disks.size(); ++d) {
        const std::complex<double> x = r.q(lin.dof(lin.disks[d].node, kX)), y = r.q(lin.dof(lin.disks[d].node, kY));
        const double radius = major_semi_axis(x, y);
        EXPECT_NEAR(p.disk_radius[d] / radius, 1.0, tolerance)
            << "disk " << d << " at " << p.speed / kRpmToRadPerS << " rpm";
        EXPECT_NEAR(std::remainder(p.disk_phase[d] - std::arg(x), 2 * M_PI), 0.0, tolerance);
        *worst = std::max(*worst, std::abs(p.disk_radius[d] / radius - 1.0));
      }
      for (std::size_t b = 0; b < lin.bearings.size(); ++b) {
        const double f = std::abs(r.bearing_fx[b]);
        EXPECT_NEAR(p.bearing_force[b] / f, 1.0, tolerance) << "bearing " << b << " at " << p.speed / kRpmToRadPerS;
      }
    }
}

TEST(UnbalanceWhirl, OnLinearBearingsItIsTheLinearResponse) {
  // examples/reference_linear.toml with cross-coupled stiffness and damping (the same in every direction): the
  // turning frame's statics with the damping acting on the whirl's velocity against the inertial frame's complex
  // amplitudes (model/rotor/response.h), a different computation.
  MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_linear.toml");
  spec.bearings.at(0).linear.k[1] = {2e6};  // kxy
  spec.bearings.at(0).linear.k[2] = {-2e6};  // kyx
  spec.bearings.at(1).linear.c[1] = {50.0};  // cxy
  spec.bearings.at(1).linear.c[2] = {-50.0};  // cyx
  const Rotor rotor = build_rotor(spec);
  UnbalanceWhirlOptions o;
  o.start_speed = 5000 * kRpmToRadPerS;
  o.end_speed = 150000 * kRpmToRadPerS;
  const UnbalanceWhirl nl = nonlinear_unbalance_response(spec, rotor, o);
  ASSERT_EQ(nl.pieces.size(), 1u) << nl.pieces[0].stopped;
  EXPECT_TRUE(nl.covers_range);
  EXPECT_TRUE(nl.pieces[0].folds.empty());
  EXPECT_GT(nl.pieces[0].points.size(), 50u);
  EXPECT_NEAR(nl.pieces[0].points.back().speed / o.end_speed, 1.0, 1e-12);
  double worst = 0.0;
  expect_linear_response(nl, rotor, 1e-6, &worst);
  for (const UnbalanceWhirlPoint& p : nl.pieces[0].points) EXPECT_TRUE(p.stable) << p.speed / kRpmToRadPerS << " rpm";
  std::printf("[ linear ] %zu points, largest difference %.2e\n", nl.pieces[0].points.size(), worst);
}

TEST(UnbalanceWhirl, BallBearingsAtASmallUnbalanceAreTheLinearisedResponse) {
  // examples/reference_ball.toml with a thousandth of its unbalance: whirls of nanometres, where the ball bearings'
  // reaction is their quasi-static linearisation (`turbodyn response` on ball bearings). Compared away from the two
  // forward criticals (548.3 and 700.1 Hz), where the linearised response has the contacts' damping and the
  // nonlinear one none (10 % away, where that damping and the whirls' own nonlinearity move it by about 1e-3).
  const MachineSpec spec =
      load_model(testing::source_dir() + "/examples/reference_ball.toml",
                 {parse_override("disks.compressor.unbalance=0.39 mg*mm"),
                  parse_override("disks.turbine.unbalance=0.58 mg*mm")});
  const Rotor rotor = build_rotor(spec);
  Rotor lin = build_rotor(spec);
  add_ball_bearing_linearisations(spec, lin);
  UnbalanceWhirlOptions o;
  o.start_speed = 10000 * kRpmToRadPerS;
  o.end_speed = 80000 * kRpmToRadPerS;
  const UnbalanceWhirl nl = nonlinear_unbalance_response(spec, rotor, o);
  EXPECT_TRUE(nl.covers_range);
  // Undamped, the curve still climbs each resonance to large whirls (then a second piece comes down from the top
  // speed): only the small whirls away from the criticals are the linear ones.
  UnbalanceWhirl away = nl;
  std::size_t compared = 0, total = 0;
  for (UnbalanceWhirlPiece& piece : away.pieces) {
    auto& pts = piece.points;
    total += pts.size();
    pts.erase(std::remove_if(pts.begin(), pts.end(),
                             [](const UnbalanceWhirlPoint& p) {
                               const double f = p.speed / (2 * M_PI);
                               return std::abs(f / 548.3 - 1.0) < 0.1 || std::abs(f / 700.1 - 1.0) < 0.1 ||
                                      std::max(p.disk_radius[0], p.disk_radius[1]) > 0.1e-6;
                             }),
              pts.end());
    compared += pts.size();
  }
  ASSERT_GT(compared, 50u);
  double worst = 0.0;
  // The linearised rotor's bearings are LinearBearings; the nonlinear response lists them in the same model order.
  expect_linear_response(away, lin, 2e-3, &worst);
  std::printf("[ ball, small ] %zu of %zu points compared, largest difference %.2e\n", compared, total, worst);
}

TEST(UnbalanceWhirl, ARigidSymmetricRotorFollowsItsBearingsLoadDeflectionCurve) {
  // Closed form: a rigid rotor, symmetric about its middle, with equal unbalances U at the same angle on both
  // wheels, whirls in its cylindrical mode without tilt. In the turning frame the bearings hold the rotor's
  // centrifugal force: 2 F(A, Omega) = Omega^2 (m A + 2U), A the whirl radius signed along the unbalance (negative
  // above the critical speed), F the load-deflection curve (another driver of the quasi-static model). The shaft
  // and wheels as in the backbone's rigid-rotor test (bending at the 1e-3 level).
  const MachineSpec spec = testing::rigid_symmetric_ball_rotor(
      {"disks.turbine.unbalance=390 mg*mm", "disks.turbine.unbalance_phase=90 deg"});
  const BallBearingElement element("compressor", spec.bearings.at(0).ball, 0, 0.0);
  const BallBearingQuasiStatic qs(element);
  const Rotor rotor = build_rotor(spec);
  const double m = rotor.total_mass, U = 2 * 390e-9;
  UnbalanceWhirlOptions o;
  o.start_speed = 20000 * kRpmToRadPerS;
  o.end_speed = 100000 * kRpmToRadPerS;
  const UnbalanceWhirl nl = nonlinear_unbalance_response(spec, rotor, o);
  int checked = 0;
  double worst = 0.0, largest = 0.0;
  for (const UnbalanceWhirlPiece& piece : nl.pieces)
    for (const UnbalanceWhirlPoint& p : piece.points) {
      const double r = p.disk_radius[0];
      if (r < 1e-7) continue;
      EXPECT_NEAR(p.disk_radius[1] / r, 1.0, 2e-3);  // a rigid translation
      const double a = std::cos(p.disk_phase[0] - M_PI / 2) > 0.0 ? r : -r;
      const double force = qs.load_deflection(p.speed, {r}).back().load;
      const double expected = 2.0 * force * (a / r) / (m * a + U);  // Omega^2
      ASSERT_GT(expected, 0.0) << "at " << p.speed / kRpmToRadPerS << " rpm, radius " << r;
      const double e = std::sqrt(expected) / p.speed - 1.0;
      EXPECT_NEAR(e, 0.0, 2e-3) << "at " << p.speed / kRpmToRadPerS << " rpm, radius " << r * 1e6 << " um";
      worst = std::max(worst, std::abs(e));
      largest = std::max(largest, r);
      ++checked;
    }
  EXPECT_GT(checked, 30);
  EXPECT_GT(largest, 10e-6);
  std::printf("[ rigid ] %d points to %.1f um, largest speed difference %.2e\n", checked, largest * 1e6, worst);
}

TEST(UnbalanceWhirl, VariantTwosFirstCriticalFoldsIntoAHysteresisLoop) {
  // examples/reference_ball.toml: the first forward critical softens (backbone 548.3 -> 469 Hz at 60 um of the
  // turbine wheel) and then hardens, so its unbalance response folds. The branch below it turns back where a slow
  // run-up jumps up; the branch above it (which neither end of the range reaches: found from a seed) turns forward
  // where a slow run-down jumps down. Variant II's run-up and run-down through it at 1/64 of the paper's rate
  // (docs/ball-bearing.md "Nonlinear unbalance response") jump at 517.4 and 477.3 Hz: the run-down's fold (a whirl of
  // some 60 um, where the race traction saturates) to 1 %, the run-up's (13 um) some 4 % below (the quasi-static
  // bearing has no race traction, whose creep stiffens the full model's bearings at small motions: `turbodyn
  // stability`).
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  const Rotor rotor = build_rotor(spec);
  UnbalanceWhirlOptions o;
  o.start_speed = 10000 * kRpmToRadPerS;
  o.end_speed = 40000 * kRpmToRadPerS;
  const UnbalanceWhirl nl = nonlinear_unbalance_response(spec, rotor, o);
  ASSERT_FALSE(nl.pieces.empty());
  EXPECT_TRUE(nl.covers_range);
  const UnbalanceWhirlPiece& up = nl.pieces[0];
  ASSERT_GE(up.folds.size(), 1u) << up.stopped;
  // The run-up's jump: where the branch continued from the lowest speed first turns back.
  const UnbalanceWhirlFold& jump_up = up.folds[0];
  EXPECT_TRUE(jump_up.speed_turns_back);
  // The run-down's jump: the fold where the speed turns forward on the branch continued downwards from above the
  // critical (a seed's).
  const UnbalanceWhirlFold* jump_down = nullptr;
  for (std::size_t k = 1; k < nl.pieces.size(); ++k) {
    const UnbalanceWhirlPiece& p = nl.pieces[k];
    if (p.upward || p.start_speed < 2 * M_PI * 500.0 || p.start_speed > 2 * M_PI * 600.0) continue;
    for (const UnbalanceWhirlFold& f : p.folds)
      if (!f.speed_turns_back && !jump_down) jump_down = &f;
  }
  ASSERT_NE(jump_down, nullptr) << "no branch from above the first critical folds";
  const double f_up = jump_up.speed / (2 * M_PI), f_down = jump_down->speed / (2 * M_PI);
  EXPECT_LT(f_up, 548.3);
  EXPECT_LT(f_down, f_up);
  EXPECT_GT(jump_down->largest_radius, jump_up.largest_radius);
  // Stable up to the run-up's fold, unstable (a saddle: a real eigenvalue) from there to the next fold, stable again
  // on the resonant branch after it.
  std::size_t k = 0;
  while (k < up.points.size() && up.points[k].speed < jump_up.speed * (1.0 - 1e-3)) EXPECT_TRUE(up.points[k++].stable);
  while (k < up.points.size() && up.points[k].speed > up.folds.at(1).speed * (1.0 + 1e-3)) {
    if (up.points[k].speed < jump_up.speed * (1.0 - 1e-3)) {
      EXPECT_FALSE(up.points[k].stable) << up.points[k].speed / (2 * M_PI) << " Hz";
      EXPECT_GT(up.points[k].divergence_rate, 1.0);
    }
    ++k;
  }
  ASSERT_LT(k, up.points.size());
  for (++k; k < up.points.size(); ++k) EXPECT_TRUE(up.points[k].stable) << up.points[k].speed / (2 * M_PI) << " Hz";
  EXPECT_NEAR(f_down / 477.3, 1.0, 0.01);
  EXPECT_NEAR(f_up / 517.4, 1.0, 0.05);
  EXPECT_LT(f_up, 517.4);
  // Below the loop the response is the lower branch; at 349 Hz the full model's slow run-up (1/16 of the paper's
  // rate) has 0.72 and 1.33 um at the compressor and turbine wheels.
  int compared = 0;
  for (const UnbalanceWhirlPoint& p : up.points)
    if (std::abs(p.speed / (2 * M_PI) - 349.1) < 2.0) {
      EXPECT_NEAR(p.disk_radius[0] / 0.72e-6, 1.0, 0.08);
      EXPECT_NEAR(p.disk_radius[1] / 1.33e-6, 1.0, 0.08);
      ++compared;
    }
  EXPECT_GT(compared, 0);
  std::printf("[ ball ] run-up jump %.1f Hz (%.1f um), run-down jump %.1f Hz (%.1f um); %zu pieces\n", f_up,
              jump_up.largest_radius * 1e6, f_down, jump_down->largest_radius * 1e6, nl.pieces.size());
}

TEST(UnbalanceWhirl, RefusesWhatItCannotTake) {
  const MachineSpec ball = load_model(testing::source_dir() + "/examples/reference_ball.toml");
  const Rotor rotor = build_rotor(ball);
  UnbalanceWhirlOptions o;
  o.start_speed = 2000.0;
  o.end_speed = 1000.0;
  EXPECT_THROW(nonlinear_unbalance_response(ball, rotor, o), std::invalid_argument);
  o.start_speed = 0.0;
  o.end_speed = 1000.0;
  EXPECT_THROW(nonlinear_unbalance_response(ball, rotor, o), std::invalid_argument);
  o.start_speed = 1000.0;
  o.end_speed = 3000.0;
  const MachineSpec sfd = load_model(testing::source_dir() + "/examples/reference_ball_sfd.toml");
  try {
    nonlinear_unbalance_response(sfd, build_rotor(sfd), o);
    ADD_FAILURE() << "a ball bearing in a damper accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("squeeze-film damper"), std::string::npos) << e.what();
  }
  MachineSpec aniso = load_model(testing::source_dir() + "/examples/reference_linear.toml");
  aniso.bearings.at(0).linear.k[3] = {2e7};  // kyy != kxx
  try {
    nonlinear_unbalance_response(aniso, build_rotor(aniso), o);
    ADD_FAILURE() << "an anisotropic bearing accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the same in every direction"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace turbodyn
