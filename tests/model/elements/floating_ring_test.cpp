// Full-floating-ring bearing element: shaft and ring forces in opposition, invariance of the inner film under the
// ring's angle, and the drill holes' period.
#include "model/elements/floating_ring_element.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"
#include "tests/support/element_differences.h"
#include "tests/support/floating_ring_fixtures.h"

namespace turbodyn {
namespace {

using testing::reference_ring;

// Shaft forces and ring derivatives at one state (`ring` = the 10 ring states).
struct Eval {
  double f[4] = {0, 0, 0, 0};
  double zdot[FloatingRingElement::kStates] = {};
};
Eval evaluate(const FloatingRingElement& e, ElementWorkspace& ws, double W, const double* q, const double* v,
              const double* ring) {
  Eval r;
  e.calc_and_add_forces(SpinState{0.0, W, 0.0, 0.0}, q, v, ring, ws, r.f, r.zdot);
  return r;
}

// A general state: journal off-centre, moving and tilted in the ring; the ring off-centre, moving, tilted, spinning.
void general_state(double* q, double* v, double* z) { testing::general_ring_state(q, v, z); }

TEST(FloatingRing, FilmForcesActOnShaftAndRingInOpposition) {
  // Journal displaced in +x inside a centred ring: the inner film pushes the journal back (-x) and the ring the
  // other way (Newton's third law through the film).
  const FloatingRingSpec f = reference_ring();
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 0.0);
  auto ws = e.make_workspace();
  const double q[4] = {5e-6, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  double z[FloatingRingElement::kStates] = {};
  z[FloatingRingElement::kSpin] = 1000.0;
  double fs[4] = {0, 0, 0, 0}, zdot[FloatingRingElement::kStates];
  e.calc_and_add_forces(SpinState{0.0, 3141.0, 0.0, 0.0}, q, v, z, *ws, fs, zdot);
  EXPECT_LT(fs[0], 0.0);
  EXPECT_GT(zdot[2], 0.0);  // the ring (centred in its own film, which carries no force there) is pushed to +x
}

TEST(FloatingRing, ThinnestFilmProbesIncludeTheRingsOffsetAndTilt) {
  // Ring 0.3 c_o off in +x and tilted in the x-z plane so that its ends lie a further 0.2 c_o out; the journal
  // 0.2 c_i beyond the ring's centre, untilted. Outer film: c_o - 0.5 c_o. Inner film: the journal against the
  // tilted ring, its ends 0.2 c_i + (L_i / 2) * tilt off the ring's axis.
  FloatingRingSpec f = reference_ring();
  f.film_thickness_limit = 1e-6;
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 0.0);
  auto ws = e.make_workspace();
  const double ci = f.inner_clearance, co = f.outer_clearance;
  const double tilt = 0.2 * co / (0.5 * f.outer_length);
  double z[FloatingRingElement::kStates] = {};
  z[FloatingRingElement::kX] = 0.3 * co;
  z[FloatingRingElement::kAy] = tilt;  // dx/dz of the ring's axis
  z[FloatingRingElement::kSpin] = 1000.0;
  z[FloatingRingElement::kAngle] = 0.7;  // the ring's angle does not matter
  const double q[4] = {0.3 * co + 0.2 * ci, 0, 0, 0}, v[4] = {0, 0, 0, 0};
  const std::vector<ProbeInfo> info = e.probes();
  std::vector<double> out(info.size());
  e.eval_probes(SpinState{0.0, 3000.0, 0.0, 0.0}, q, v, z, *ws, out.data());
  int seen = 0;
  for (std::size_t i = 0; i < info.size(); ++i) {
    if (info[i].name == "inner_min_film_thickness") {
      EXPECT_NEAR(out[i], ci - 0.2 * ci - 0.5 * f.inner_length * tilt, 1e-12 * ci);
      ++seen;
    } else if (info[i].name == "outer_min_film_thickness") {
      EXPECT_NEAR(out[i], 0.5 * co, 1e-12 * co);
      ++seen;
    } else {
      continue;
    }
    EXPECT_EQ(info[i].limit, 1e-6);  // one permissible thickness for both films
    EXPECT_TRUE(info[i].limit_below);
  }
  EXPECT_EQ(seen, 2);
}

TEST(FloatingRing, AnOuterFeedGrooveHoldsEveryDrillHoleAtTheSupplyPressure) {
  // A circumferential groove in the housing bore at mid-width holds the drill holes' outer mouths at the supply
  // pressure wherever the ring turns and moves; fed through the single top hole they see the outer film's pressure
  // where they pass, which varies with the ring's angle. The oil column spinning with the ring lowers the inner
  // mouths' pressure by 1/2 rho w^2 (r_o^2 - r_i^2).
  FloatingRingSpec hole = reference_ring();
  hole.drill_holes = 4;
  hole.drill_hole_diameter = 0.002;
  hole.drill_hole_centrifugal = false;
  FloatingRingSpec groove = hole;
  groove.feed_hole_diameter = 0.0;
  groove.feed_groove_width = 0.002;  // covers the two middle rows of the 12
  FloatingRingSpec spinning = groove;
  spinning.drill_hole_centrifugal = true;
  OilSpec oil;
  const FloatingRingElement eh("hole", hole, oil, 0, 0.0), eg("groove", groove, oil, 0, 0.0),
      es("spinning", spinning, oil, 0, 0.0);
  double q[4], v[4], z[FloatingRingElement::kMaxStates];
  general_state(q, v, z);
  const double ro = 0.5 * groove.outer_diameter, ri = 0.5 * groove.inner_diameter;
  const double head = 0.5 * oil.density * z[FloatingRingElement::kSpin] * z[FloatingRingElement::kSpin] *
                      (ro * ro - ri * ri);
  auto hole_pressure = [&](const FloatingRingElement& e) {
    auto ws = e.make_workspace();
    const std::vector<ProbeInfo> info = e.probes();
    std::vector<double> out(info.size());
    e.eval_probes(SpinState{0.0, 3000.0, 0.0, 0.0}, q, v, z, *ws, out.data());
    for (std::size_t i = 0; i < info.size(); ++i)
      if (info[i].name == "drill_hole_pressure") return out[i];
    ADD_FAILURE() << "no drill_hole_pressure probe";
    return 0.0;
  };
  double lo = 1e30, hi = -1e30;
  for (const double angle : {0.0, 0.3, 0.6, 1.1}) {
    z[FloatingRingElement::kAngle] = angle;
    EXPECT_NEAR(hole_pressure(eg), groove.supply_pressure, 1e-9 * groove.supply_pressure) << angle;
    EXPECT_NEAR(hole_pressure(es), groove.supply_pressure - head, 1e-9 * groove.supply_pressure) << angle;
    lo = std::min(lo, hole_pressure(eh));
    hi = std::max(hi, hole_pressure(eh));
  }
  EXPECT_GT(head, 1e4);
  EXPECT_GT(hi - lo, 1e3);  // through the hole the drill holes' pressure depends on where they are
  EXPECT_LT(hi, hole.supply_pressure);
}

TEST(FloatingRing, InnerFilmInTheRingFrameGivesTheSameForcesAtAnyRingAngle) {
  // Without drill holes nothing is fixed in the ring frame, so the forces must not depend on the ring angle: checks
  // the rotation of positions, tilts and their rates (with the frame-rotation terms) into the ring frame and back.
  FloatingRingSpec f = reference_ring();
  f.n_circ = 72;
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 0.0);
  auto ws = e.make_workspace();
  double q[4], v[4], z[FloatingRingElement::kMaxStates];
  general_state(q, v, z);
  const double W = 3000.0;
  const Eval a = evaluate(e, *ws, W, q, v, z);
  for (double phi : {0.3, 2.0, 17.0}) {  // not multiples of the grid pitch: the film is re-gridded in the ring frame
    z[FloatingRingElement::kAngle] = phi;
    const Eval b = evaluate(e, *ws, W, q, v, z);
    const double fscale = std::hypot(a.f[0], a.f[1]), mscale = std::hypot(a.f[2], a.f[3]);
    // Discretisation: the film's pressure field is sampled at other points of the journal when rotated.
    EXPECT_NEAR(b.f[0], a.f[0], 0.01 * fscale) << phi;
    EXPECT_NEAR(b.f[1], a.f[1], 0.01 * fscale) << phi;
    EXPECT_NEAR(b.f[2], a.f[2], 0.02 * mscale) << phi;
    EXPECT_NEAR(b.f[3], a.f[3], 0.02 * mscale) << phi;
    EXPECT_NEAR(b.zdot[FloatingRingElement::kSpin], a.zdot[FloatingRingElement::kSpin],
                1e-3 * std::abs(a.zdot[FloatingRingElement::kSpin]));
  }
  // A quarter turn maps the 72-node grid onto itself: then the agreement is exact to the solver tolerance.
  z[FloatingRingElement::kAngle] = M_PI / 2;
  const Eval c = evaluate(e, *ws, W, q, v, z);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(c.f[k], a.f[k], 1e-6 * std::hypot(a.f[0], a.f[1]) + 1e-9) << k;
}

TEST(FloatingRing, FourDrillHolesRepeatEveryQuarterTurnOfTheRing) {
  FloatingRingSpec f = reference_ring();
  f.drill_holes = 4;
  f.drill_hole_diameter = 0.002;
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 0.0);
  auto ws = e.make_workspace();
  double q[4], v[4], z[FloatingRingElement::kMaxStates];
  general_state(q, v, z);
  z[FloatingRingElement::kAngle] = 0.4;
  const Eval a = evaluate(e, *ws, 3000.0, q, v, z);
  z[FloatingRingElement::kAngle] = 0.4 + M_PI / 2;
  const Eval b = evaluate(e, *ws, 3000.0, q, v, z);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(b.f[k], a.f[k], 1e-6 * std::abs(a.f[k]) + 1e-9) << k;
  for (int k = 0; k < FloatingRingElement::kStates; ++k)
    EXPECT_NEAR(b.zdot[k], a.zdot[k], 1e-6 * std::abs(a.zdot[k]) + 1e-9) << k;
  // The holes feed the inner film: its load capacity differs from the unfed film's.
  FloatingRingSpec closed = reference_ring();
  const FloatingRingElement ec("closed", closed, oil, 0, 0.0);
  auto wc = ec.make_workspace();
  const Eval c = evaluate(ec, *wc, 3000.0, q, v, z);
  EXPECT_GT(std::abs(c.f[0] - a.f[0]) + std::abs(c.f[1] - a.f[1]), 1e-3 * std::hypot(a.f[0], a.f[1]));
}

// The element's own Jacobian (the base factorisations reused for every column: back-substitutions for the rates, one
// Newton step for the thickness columns; the outer film skipped for the shaft's)
// against plain forward differences of calc_and_add_forces, which solve both films anew for every column. Each
// entry is compared in units of its row's largest change over a typical step of the inputs (the engine's Newton
// matrix weighs them that way); forward differences with relative steps of 1e-6 of an iterative active-set solve
// agree to about sqrt(1e-6) = 1e-3 of that (Pinocchio and Ceres' GradientChecker use the same sqrt(h) rule).
TEST(FloatingRing, OwnJacobianMatchesPlainFiniteDifferences) {
  for (const bool tilt : {true, false}) {
    FloatingRingSpec f = reference_ring();
    f.drill_holes = 4;
    f.drill_hole_diameter = 0.002;
    f.ring_tilt = tilt;
    OilSpec oil;
    const FloatingRingElement e("test", f, oil, 0, 9.81);
    ASSERT_TRUE(e.has_jacobian());
    auto ws = e.make_workspace();
    double q[4], v[4], z[FloatingRingElement::kMaxStates];
    general_state(q, v, z);
    z[FloatingRingElement::kAngle] = 0.4;
    const SpinState s{0.0, 3000.0, 50.0, 0.0};
    constexpr int d = 4, m = FloatingRingElement::kStates, rows = d + m, cols = 2 * d + m;
    // Plain forward differences with the element's own steps.
    const std::vector<double> out0 = testing::element_outputs(e, s, q, v, z, m, *ws);
    const std::vector<double> fd = testing::forward_differences(e, s, q, v, z, m, *ws);
    // Own Jacobian at the same state, twice (the second call must not be disturbed by the first's perturbations).
    std::vector<double> own(rows * cols, 0.0), again(rows * cols, 0.0);
    e.add_jacobian(s, q, v, z, *ws, own.data());
    e.add_jacobian(s, q, v, z, *ws, again.data());
    constexpr double kTolerance = 1e-3;  // sqrt of the relative step
    auto skipped_tilt = [&](int j) {  // never used without tilt: the tilt states do not move
      return !tilt && (j == 2 * d + FloatingRingElement::kAx || j == 2 * d + FloatingRingElement::kAy ||
                       j == 2 * d + FloatingRingElement::kWx || j == 2 * d + FloatingRingElement::kWy);
    };
    for (int j = 0; j < cols; ++j) {
      if (!skipped_tilt(j)) continue;
      for (int r = 0; r < rows; ++r) EXPECT_EQ(own[j * rows + r], 0.0) << "row " << r << ", column " << j;
    }
    testing::expect_jacobian_near(e, own, fd, m, kTolerance, skipped_tilt, tilt ? "" : ", no tilt");
    testing::expect_jacobian_near(e, again, own, m, 1e-8, skipped_tilt, ", second call");
    // The forces at the state are still those of the state after the Jacobian's perturbed solves.
    EXPECT_EQ(testing::element_outputs(e, s, q, v, z, m, *ws), out0);
  }
}

// The integrator's tolerances of the ring's states (RunupModel::AbsoluteTolerances with atol_scaling "typical")
// follow state_scale: its tilts and tilt rates are the rotations that move the wider film's edges (z = +-L/2) by
// the typical translation and translational velocity, so no state of the ring is resolved more finely than the
// film thickness it changes.
TEST(FloatingRing, TiltTolerancesMoveTheFilmEdgeAsMuchAsTheTranslations) {
  FloatingRingSpec f = reference_ring();
  f.inner_length = 0.007;
  f.outer_length = 0.010;
  OilSpec oil;
  const FloatingRingElement e("test", f, oil, 0, 9.81);
  using R = FloatingRingElement;
  const double half = 0.005;
  EXPECT_DOUBLE_EQ(e.state_scale(R::kAx) * half, e.state_scale(R::kX));
  EXPECT_DOUBLE_EQ(e.state_scale(R::kAy) * half, e.state_scale(R::kY));
  EXPECT_DOUBLE_EQ(e.state_scale(R::kWx) * half, e.state_scale(R::kVx));
  EXPECT_DOUBLE_EQ(e.state_scale(R::kWy) * half, e.state_scale(R::kVy));
  EXPECT_DOUBLE_EQ(e.state_scale(R::kX), ForceElement::kTypicalDisplacement);
  EXPECT_DOUBLE_EQ(e.state_scale(R::kVx), ForceElement::kTypicalVelocity);
  f.inner_length = 0.012;  // the inner film the wider one
  const FloatingRingElement wide("test", f, oil, 0, 9.81);
  EXPECT_DOUBLE_EQ(wide.state_scale(R::kAx) * 0.006, wide.state_scale(R::kX));
}

}  // namespace
}  // namespace turbodyn
