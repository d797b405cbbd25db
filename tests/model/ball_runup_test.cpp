// The reference rotor in multibody ball bearings (variant II) and in ball bearings in squeeze-film dampers
// (variant III): short run-ups through the engine, checked against the bearing kinematics and the energy balance.
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
#include "tests/model/test_support.h"

namespace turbodyn {
namespace {

RunupResult run(const std::string& example, const std::vector<Override>& o) {
  const MachineSpec spec = load_model(testing::source_dir() + "/examples/" + example, o);
  const auto model = make_runup_model(spec);
  return simulate_runup(*model, runup_options(spec));
}

const std::vector<double>& channel(const RunupResult& r, const std::string& name) {
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    if (r.channels[c].name == name) return r.columns[c];
  throw std::runtime_error("no channel " + name);
}

// Mean of a channel over the last `fraction` of the samples.
double late_mean(const RunupResult& r, const std::string& name, double fraction) {
  const std::vector<double>& x = channel(r, name);
  const std::size_t a = static_cast<std::size_t>((1.0 - fraction) * x.size());
  double s = 0;
  for (std::size_t i = a; i < x.size(); ++i) s += x[i];
  return s / double(x.size() - a);
}

double peak(const RunupResult& r, const std::string& name) {
  double m = 0;
  for (double x : channel(r, name)) m = std::max(m, std::abs(x));
  return m;
}

// The paper's acceleration (150,000 rpm in 4 s) up to 6,000 rpm.
const std::vector<Override> kShortRamp = {{"speed.end", "6000 rpm"}, {"speed.duration", "0.16"}};

TEST(BallRunup, CageFollowsTheKinematicsAndTheEnergyBalanceCloses) {
  const RunupResult r = run("reference_ball.toml", kShortRamp);
  ASSERT_TRUE(r.complete) << r.message;
  // Cage speed of an angular-contact bearing with a rotating inner ring and a fixed outer ring, pure rolling:
  // w_c / W = (1 - D cos(a) / d_m) / 2 (Harris & Kotzalas 2007, §8.2), at the loaded contact angle of the run.
  constexpr double kKinematicTolerance = 0.02;  // issue 5: within 2 % of the kinematic formula
  const double D = 4.5e-3, dm = 17.5e-3;
  for (const char* b : {"compressor", "turbine"}) {
    const std::string p = std::string("bearing.") + b + ".";
    const double alpha = 0.5 * (late_mean(r, p + "inner_contact_angle", 0.1) + late_mean(r, p + "outer_contact_angle", 0.1));
    const double kinematic = 0.5 * (1.0 - D * std::cos(alpha) / dm);
    EXPECT_NEAR(late_mean(r, p + "cage_speed_ratio", 0.1) / kinematic, 1.0, kKinematicTolerance) << b;
  }
  // Contact damping and friction enter the balance through the element's dissipated_power.
  const double error = r.energy_final - r.energy_initial - r.work_in + r.dissipated;
  EXPECT_LT(std::abs(error), 1e-2 * std::max(r.work_in, r.dissipated)) << r.work_in << " " << r.dissipated;
}

TEST(BallRunup, ARunStartingMidRampStartsBallsAndCageAtTheirKinematicSpeeds) {
  // A study's speed window starts the run in the middle of the ramp: the balls and cage must start rolling at
  // their no-slip speeds (cage (1 - D cos(a) / d_m) / 2 of the rotor speed), not at rest on a spinning shaft,
  // which would put a spin-up transient of the whole bearing into the window. 30,000 rpm, the paper's ramp.
  constexpr double kKinematicTolerance = 0.02;
  const std::vector<Override> o = {{"speed.start", "30000 rpm"}, {"speed.end", "30600 rpm"}, {"speed.duration", "0.016"}};
  const RunupResult r = run("reference_ball.toml", o);
  ASSERT_TRUE(r.complete) << r.message;
  const double D = 4.5e-3, dm = 17.5e-3;
  const std::vector<double>& ratio = channel(r, "bearing.compressor.cage_speed_ratio");
  const double alpha = 0.5 * (channel(r, "bearing.compressor.inner_contact_angle").front() +
                              channel(r, "bearing.compressor.outer_contact_angle").front());
  const double kinematic = 0.5 * (1.0 - D * std::cos(alpha) / dm);
  for (std::size_t i = 0; i < ratio.size(); ++i)
    ASSERT_NEAR(ratio[i] / kinematic, 1.0, kKinematicTolerance) << "sample " << i;
}

TEST(BallRunup, BallBearingsInDampersRunAndBalanceTheirEnergy) {
  const RunupResult r = run("reference_ball_sfd.toml", kShortRamp);
  ASSERT_TRUE(r.complete) << r.message;
  EXPECT_LT(peak(r, "bearing.compressor.damper_eccentricity"), 1.0);
  const double error = r.energy_final - r.energy_initial - r.work_in + r.dissipated;
  EXPECT_LT(std::abs(error), 1e-2 * std::max(r.work_in, r.dissipated)) << r.work_in << " " << r.dissipated;
}

}  // namespace
}  // namespace turbodyn

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

}  // namespace
}  // namespace turbodyn

namespace turbodyn {
namespace {

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
