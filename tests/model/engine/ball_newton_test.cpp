// The Newton solve of the run-up engine with ball bearings: the balls' blocks are independent, the block solve
// matches the full system, and the bearing's own Jacobian matches plain finite differences.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/elements/ball/ball_bearing.h"
#include "model/elements/ball/ball_damper_element.h"
#include "model/io/model_file.h"
#include "model/engine/integrator.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

// The Newton solve eliminates each ball's 9 states on their own (BallBearingElement::independent_state_blocks)
// and then the cage and outer ring. That rests on the balls' equations not involving one another: the
// finite-difference Jacobian must have exact zeros there, and the block solve must satisfy the full system
// (I - gamma dF/dy) x = b to round-off, for the bearing and for the bearing in a damper.
TEST(BallNewton, BallBlocksAreIndependentAndTheBlockSolveMatchesTheFullSystem) {
  constexpr double kResidualTolerance = 1e-10;
  for (const std::string example : {"reference_ball.toml", "reference_ball_sfd.toml"}) {
    const MachineSpec spec =
        load_model(testing::source_dir() + "/examples/" + example, {{"speed.start", "60000 rpm"}});
    const auto model = make_runup_model(spec);
    auto ws = model->make_workspace();
    const int ny = model->n_states();
    Eigen::VectorXd y(ny);
    model->InitialState(0.0, false, y.data(), *ws);
    y.head(2 * model->n_dof()) += Eigen::VectorXd::Random(2 * model->n_dof()) * 1e-6;  // off the rest state
    const Eigen::MatrixXd J = model->JacobianMatrix(0.0, y.data(), *ws);
    for (std::size_t k = 0; k < model->elements().size(); ++k) {
      const std::vector<int> blocks = model->elements()[k]->independent_state_blocks();
      ASSERT_FALSE(blocks.empty()) << example;
      const int z0 = model->state_offset(static_cast<int>(k));
      for (std::size_t a = 0, oa = 0; a < blocks.size(); oa += blocks[a], ++a)
        for (std::size_t b = 0, ob = 0; b < blocks.size(); ob += blocks[b], ++b)
          if (a != b) {
            EXPECT_EQ(J.block(z0 + oa, z0 + ob, blocks[a], blocks[b]).cwiseAbs().maxCoeff(), 0.0)
                << example << ": ball " << a << " depends on ball " << b;
          }
      EXPECT_GT(J.block(z0, z0, blocks[0], blocks[0]).cwiseAbs().maxCoeff(), 0.0);
    }
    for (const double gamma : {1e-7, 1e-5})
      EXPECT_LT(testing::newton_solve_residual(*model, *ws, J, gamma), kResidualTolerance)
          << example << ", gamma " << gamma;
  }
}

// The ball bearing's own finite differences (all balls' state i perturbed at once, told apart by their shares of the
// sums) against plain forward differences, one input at a time, with the same steps: the same Jacobian to
// round-off, for rings held fixed and for rings on the housing spring.
TEST(BallNewton, BallBearingJacobianMatchesPlainFiniteDifferences) {
  constexpr double kTolerance = 1e-6;  // relative to the largest entry of the column
  // Outer ring fixed, on a spring, in a squeeze-film damper (the damper element's own Jacobian).
  for (const std::string outer : {"fixed", "spring", "damper"}) {
    const bool damper = outer == "damper";
    std::vector<Override> set = {{"speed.start", "60000 rpm"}};
    if (!damper)
      set.insert(set.end(), {{"bearings.compressor.outer_ring", outer}, {"bearings.turbine.outer_ring", outer}});
    const MachineSpec spec = load_model(
        testing::source_dir() + (damper ? "/examples/reference_ball_sfd.toml" : "/examples/reference_ball.toml"), set);
    const auto model = make_runup_model(spec);
    auto rws = model->make_workspace();
    Eigen::VectorXd y(model->n_states());
    model->InitialState(0.0, false, y.data(), *rws);
    const SpinState s = model->spin(0.0);
    const ForceElement& e = *model->elements()[0];
    ASSERT_TRUE(e.has_jacobian());
    auto ws = e.make_workspace();
    const int d = static_cast<int>(e.dofs().size()), m = e.n_states(), rows = d + m, cols = 2 * d + m;
    Eigen::VectorXd in(cols);
    in << Eigen::VectorXd::Random(d) * 2e-6, Eigen::VectorXd::Random(d) * 1e-3,
        y.segment(model->state_offset(0), m);
    // Turn the cage ahead by more than the pocket clearance over the pitch radius, so that every ball touches its
    // pocket and the cage's rows depend on the balls.
    const auto* damper_element = dynamic_cast<const BallDamperElement*>(&e);
    const auto* bearing = damper ? &damper_element->bearing() : dynamic_cast<const BallBearingElement*>(&e);
    ASSERT_NE(bearing, nullptr);
    in(2 * d + bearing->cage_offset() + 3) += 1.3 * spec.bearings.at(0).ball.pocket_clearance /
                                              (0.5 * spec.bearings.at(0).ball.pitch_diameter);
    if (damper) {  // the ring off centre and moving, so that the film carries load
      const double c = spec.bearings.at(0).damper.clearance;
      const int r = 2 * d + bearing->n_core_states();
      in.segment(r, 4) << 0.3 * c, -0.4 * c, 2e-3, -1e-3;
    }
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, cols);
    e.add_jacobian(s, in.data(), in.data() + d, in.data() + 2 * d, *ws, J.data());
    const auto eval = [&](const Eigen::VectorXd& x) {
      Eigen::VectorXd out = Eigen::VectorXd::Zero(rows);
      e.calc_and_add_forces(s, x.data(), x.data() + d, x.data() + 2 * d, *ws, out.data(), out.data() + d);
      return out;
    };
    const Eigen::VectorXd out0 = eval(in);
    for (int j = 0; j < cols; ++j) {
      const double h = e.fd_step(j, d, in(j));
      Eigen::VectorXd x = in;
      x(j) += h;
      const Eigen::VectorXd out1 = eval(x);
      const Eigen::VectorXd col = (out1 - out0) / h;
      // The plain differences carry the round-off of the whole sum: one ball's share of the cage's torque is
      // resolved only to eps |T_cage| / h. The shares resolve it better, so the bound is the plain one's noise.
      const Eigen::VectorXd noise =
          (16.0 * std::numeric_limits<double>::epsilon() / h) * out0.cwiseAbs().cwiseMax(out1.cwiseAbs());
      const double scale = col.cwiseAbs().maxCoeff();
      const Eigen::VectorXd excess = (J.col(j) - col).cwiseAbs() - noise;
      Eigen::Index worst = 0;
      EXPECT_LT(excess.maxCoeff(&worst), kTolerance * scale)
          << outer << ", input " << j << ", row " << worst << ": " << J(worst, j) << " against " << col(worst);
    }
  }
}

}  // namespace
}  // namespace turbodyn
