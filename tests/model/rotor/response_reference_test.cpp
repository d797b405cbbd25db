// Steady-state unbalance response against the Jeffcott-type closed form.
#include "model/rotor/response.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// A short, stiff, symmetric rotor on soft isotropic supports with the unbalance at mid-span, well below its first
// bending mode, moves as a rigid body: x = U W^2 / (K - M W^2 + i C W) with the totals K = 2k, C = 2c, M
// (the Jeffcott rotor, e.g. Friswell et al. 2010, Sec. 3.3; Genta 2005, Sec. 4.2).
TEST(Response, RigidSymmetricRotorFollowsTheJeffcottFormula) {
  MachineSpec s = testing::uniform_beam(0.4, 0.05, 8, true, true);
  s.mesh.gyroscopic = true;  // cylindrical whirl does not tilt the rotor: gyroscopics play no part
  DiskSpec d;
  d.name = "mid";
  d.z = 0.2;
  d.mass = 1.0;
  d.polar_inertia = 0.01;
  d.diametral_inertia = 0.006;
  d.unbalance = 1e-4;
  d.unbalance_phase = 0.3;
  s.disks.push_back(d);
  const double k = 2e3, c = 5.0;
  for (double z : {0.0, 0.4}) {
    BearingSpec b;
    b.name = z == 0.0 ? "a" : "b";
    b.type = BearingType::Linear;
    b.z = z;
    b.linear.k = {{{k}, {0.0}, {0.0}, {k}}};
    b.linear.c = {{{c}, {0.0}, {0.0}, {c}}};
    s.bearings.push_back(b);
  }
  const Rotor rotor = build_rotor(s);
  const double M = rotor.total_mass;
  const int node = rotor.disks[0].node;
  const std::complex<double> I(0, 1);
  for (double w : {10.0, 20.0, std::sqrt(2 * k / M), 40.0, 200.0}) {
    const SteadyResponse r = unbalance_response(rotor, w);
    const std::complex<double> expected = d.unbalance * w * w * std::exp(I * d.unbalance_phase) /
                                          (2 * k - M * w * w + I * 2.0 * c * w);
    const std::complex<double> x = r.q(rotor.dof(node, kX)), y = r.q(rotor.dof(node, kY));
    EXPECT_NEAR(std::abs(x - expected) / std::abs(expected), 0.0, 1e-3) << w << " rad/s";
    EXPECT_NEAR(std::abs(y - (-I) * expected) / std::abs(expected), 0.0, 1e-3) << w << " rad/s";  // circular
    EXPECT_NEAR(major_semi_axis(x, y), std::abs(expected), 1e-3 * std::abs(expected));
    // The bearings transmit k x + i c w x each.
    EXPECT_NEAR(std::abs(r.bearing_fx[0]) / std::abs((k + I * c * w) * x), 1.0, 2e-3);
  }
}

}  // namespace
}  // namespace turbodyn
