// Shaft finite elements: invariants of the beam element's mass and gyroscopic matrices.
#include "model/rotor/timoshenko.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using testing::kRho;
using testing::solid;

TEST(BeamElement, MassAndGyroscopicInvariants) {
  const BeamProperties p = solid(0.01, 0.01, 0.886);
  const BeamElementMatrices m = beam_element(p);
  Eigen::Matrix<double, 8, 1> tx;
  tx << 1, 0, 0, 0, 1, 0, 0, 0;
  const double mass = kRho * p.area() * p.length;
  EXPECT_NEAR(tx.dot(m.mass * tx) / mass, 1.0, 1e-12);
  EXPECT_NEAR((m.mass - m.mass.transpose()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.gyroscopic + m.gyroscopic.transpose()).norm(), 0.0, 1e-18);
  // Uniform tilt theta_y = 1 of the whole element: rotary energy = rho I L, gyroscopic coupling to theta_x = 2 rho I L.
  Eigen::Matrix<double, 8, 1> ty = Eigen::Matrix<double, 8, 1>::Zero(), txr = Eigen::Matrix<double, 8, 1>::Zero();
  ty << 0, 0, 0, 1, p.length, 0, 0, 1;
  txr << 0, 0, 1, 0, 0, -p.length, 1, 0;
  EXPECT_NEAR(ty.dot(m.mass_rotary * ty) / (kRho * p.second_moment() * p.length), 1.0, 1e-10);
  EXPECT_NEAR(txr.dot(m.gyroscopic * ty) / (2 * kRho * p.second_moment() * p.length), 1.0, 1e-10);
}

}  // namespace
}  // namespace turbodyn
