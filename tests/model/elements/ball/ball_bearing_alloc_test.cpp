// The ball bearing's force evaluation allocates nothing (STYLE.md; Drake's LimitMalloc idea); the counting
// operator new comes from tests/support/alloc_counter.cpp.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "model/elements/ball/ball_bearing.h"
#include "tests/support/alloc_counter.h"

namespace turbodyn {
namespace {

TEST(BallBearingAllocation, ForceEvaluationProbesAndPowerAllocateNothing) {
  for (OuterRingMode mode : {OuterRingMode::Fixed, OuterRingMode::Spring, OuterRingMode::External})
  for (TractionLaw law : {TractionLaw::Coulomb, TractionLaw::Eyring}) {
    BallBearingSpec spec;
    spec.outer_ring_mode = mode;
    spec.traction_law = law;
    spec.lubricant_viscosity = 0.01;
    const BallBearingElement e("alloc", spec, 0, 9.81);
    auto ws = e.make_workspace();
    std::vector<double> z(e.n_states()), zdot(e.n_states()), out(e.probes().size());
    e.initial_states(z.data());
    const double W = 100000 * 2 * M_PI / 60;
    e.steady_states(W, z.data());
    z[e.cage_offset() + 3] += 0.01;  // pockets in contact
    const double q[4] = {1e-6, -0.5e-6, 1e-5, 0}, v[4] = {1e-3, 0, 0, 0};
    double f[4] = {0, 0, 0, 0};
    const SpinState s{0.0, W, 0.0, 0.0};
    e.calc_and_add_forces(s, q, v, z.data(), *ws, f, zdot.data());  // warm-up
    const long before = testing::allocation_count();
    double sink = 0.0;
    for (int i = 0; i < 100; ++i) {
      z[0] += 1e-4;
      e.calc_and_add_forces(s, q, v, z.data(), *ws, f, zdot.data());
      e.eval_probes(s, q, v, z.data(), *ws, out.data());
      sink += e.dissipated_power(s, q, v, z.data(), *ws) + e.kinetic_energy(z.data()) + e.potential_energy(q, z.data());
      BallBearingLoads loads;
      e.calc_bearing(s, q, v, z.data(), OuterRingKinematics{1e-7, 0, 0, 0}, loads, zdot.data());
      sink += loads.max_contact_force();
    }
    EXPECT_EQ(testing::allocation_count() - before, 0) << "outer-ring mode " << static_cast<int>(mode);
    EXPECT_TRUE(std::isfinite(sink));
    EXPECT_GT(f[0] * f[0] + f[1] * f[1], 0.0);
  }
  // The counter works: a vector allocates.
  const long before = testing::allocation_count();
  std::vector<double> v(10);
  EXPECT_GT(testing::allocation_count() - before, 0);
}

}  // namespace
}  // namespace turbodyn
