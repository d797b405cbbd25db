// The run-up engine against the frequency-domain solution, run-up theory, exact Jacobians, the energy balance and
// statics.
#include "model/engine/integrator.h"

#include <cmath>
#include <iostream>

#include <Eigen/Eigenvalues>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/elements/linear_bearing_element.h"
#include "model/io/model_file.h"
#include "model/rotor/response.h"
#include "post/signal.h"
#include "tests/support/test_support.h"
#include "model/spec/constants.h"

namespace turbodyn {
namespace {

using ::testing::HasSubstr;


MachineSpec reference(std::vector<Override> overrides = {}) {
  return load_model(testing::source_dir() + "/examples/reference_linear.toml", overrides);
}

// A damped pedestal under the compressor bearing: its mass's states give the model an element state block.
std::vector<Override> compressor_pedestal() {
  return {{"bearings.compressor.pedestal_mass", "0.5"},
          {"bearings.compressor.pedestal_stiffness", "2e7"},
          {"bearings.compressor.pedestal_damping", "300"}};
}

int channel(const RunupResult& r, const std::string& name) {
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    if (r.channels[c].name == name) return static_cast<int>(c);
  ADD_FAILURE() << "no channel " << name;
  return 0;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

RunupOptions options_for(const MachineSpec& spec) { return runup_options(spec); }

// The 1x order track of `probe` over a run-up of `model` (made from `spec`): `points` estimates, each over
// `revolutions` rotor revolutions. An incomplete run fails the test and gives an empty track.
signal::OrderTrack order_track_of_run(const RunupModel& model, const MachineSpec& spec, const std::string& probe,
                                      std::size_t points, double revolutions) {
  const RunupResult r = simulate_runup(model, options_for(spec));
  EXPECT_TRUE(r.complete) << r.message;
  if (!r.complete) return {};
  const int cp = channel(r, probe), cs = channel(r, "speed"), ca = channel(r, "spin_angle");
  signal::OrderTrackOptions oo;
  oo.points = points;
  oo.revolutions = revolutions;
  return signal::track_order(r.columns[cp], r.columns[ca], r.columns[cs], spec.output.sample_rate, oo);
}

TEST(SpeedFunction, RampAngleIsTheExactIntegral) {
  SpeedProfile p;
  p.start = 100.0;
  p.end = 1100.0;
  p.duration = 2.0;
  const SpeedFunction f(p);
  EXPECT_DOUBLE_EQ(f.speed(1.0), 600.0);
  EXPECT_DOUBLE_EQ(f.acceleration(1.0), 500.0);
  EXPECT_NEAR(f.angle(1.5), 100.0 * 1.5 + 0.5 * 500.0 * 1.5 * 1.5, 1e-12);
  EXPECT_NEAR(f.angle(3.0), f.angle(2.0) + 1100.0, 1e-9);  // constant speed after the ramp
  EXPECT_DOUBLE_EQ(f.acceleration(2.5), 0.0);
}

TEST(SpeedFunction, TableIsPiecewiseLinear) {
  SpeedProfile p;
  p.kind = SpeedProfile::Kind::Table;
  p.times = {0.0, 1.0, 3.0};
  p.speeds = {0.0, 100.0, 100.0};
  const SpeedFunction f(p);
  EXPECT_DOUBLE_EQ(f.speed(0.5), 50.0);
  EXPECT_NEAR(f.angle(2.0), 50.0 + 100.0, 1e-12);
}

TEST(Reduction, KeepsTheLowModesOfTheFullModel) {
  // Craig-Bampton reduction against the unreduced FE model (both with the bearings): the modes below the rotor's
  // highest speed move by less than 0.1 %.
  constexpr double kModeTolerance = 1e-3;
  const MachineSpec spec = reference();
  const auto model = make_runup_model(spec);
  ASSERT_LT(model->n_dof(), model->n_physical_dof());
  const Rotor& rotor = model->rotor();
  Eigen::MatrixXd K = rotor.K, C = rotor.D;
  rotor.add_bearings(0.0, K, C);
  const Eigen::MatrixXd& T = model->reduction_basis();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> full(K, rotor.M), red(T.transpose() * K * T, model->mass());
  for (int i = 0; i < 8; ++i) {
    const double f_full = std::sqrt(full.eigenvalues()(i)) / (2 * M_PI);
    const double f_red = std::sqrt(red.eigenvalues()(i)) / (2 * M_PI);
    if (f_full > 3000.0) break;
    EXPECT_NEAR(f_red / f_full, 1.0, kModeTolerance) << f_full << " Hz";
  }
}

TEST(Reduction, ARotorThatCanMoveRigidlyAtItsBoundaryIsAModelErrorNamingTheFileAndKey) {
  // Issue 20 (found by the input fuzzer, a model file cut short): a shaft held at one node only (here one disk, no
  // bearing) tilts freely about it; the reduction said "not stiff" in a runtime_error naming no file.
  MachineSpec spec = reference();
  spec.bearings.clear();
  spec.disks.pop_back();
  try {
    (void)make_runup_model(spec);
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("reference_linear.toml: solver.reduction_cutoff:"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("rigid body"));
  }
}

TEST(Jacobian, AssembledJacobianMatchesFiniteDifferencesOfTheRhs) {
  // Pedestal bearings add internal states; the exact rotor part, the analytic element Jacobian and the
  // scattering into the blocks are all checked against forward differences of the full right-hand side.
  MachineSpec spec = reference(compressor_pedestal());
  spec.speed.end = 60000 * kRpmToRadPerS;
  const auto model = make_runup_model(spec);
  auto ws = model->make_workspace();
  const int ny = model->n_states();
  Eigen::VectorXd y = Eigen::VectorXd::Random(ny) * 1e-5;
  const double t = 1.3;
  const Eigen::MatrixXd J = model->JacobianMatrix(t, y.data(), *ws);
  Eigen::VectorXd f0(ny), f1(ny);
  model->Rhs(t, y.data(), f0.data(), *ws);
  const int checked = ny - 2;  // the energy-accounting rows/columns are not part of the Newton system
  // The system is linear in y (linear bearings), so a difference quotient is exact up to round-off whatever the
  // step; the tolerance adds the round-off of the quotient, eps |F| / h.
  const double h = 1e-3;
  const double roundoff = 10 * std::numeric_limits<double>::epsilon() * f0.cwiseAbs().maxCoeff() / h;
  for (int j = 0; j < checked; ++j) {
    Eigen::VectorXd yp = y;
    yp(j) += h;
    model->Rhs(t, yp.data(), f1.data(), *ws);
    const Eigen::VectorXd fd = (f1 - f0) / h;
    for (int i = 0; i < checked; ++i) {
      const double scale = std::max(std::abs(J(i, j)), 1e-3 * J.col(j).head(checked).cwiseAbs().maxCoeff());
      ASSERT_NEAR(fd(i), J(i, j), 1e-6 * scale + roundoff) << "row " << i << " column " << j;
    }
  }
}

TEST(Jacobian, BlockEliminatedNewtonSolveMatchesTheFullSystem) {
  // The Newton solve eliminates each element's states block by block and factors only the rotor's Schur
  // complement; its answer must satisfy the full system (I - gamma dF/dy) x = b to round-off. Two pedestal bearings
  // of different masses give two state blocks; a step gamma of 1e-5 s weighs all blocks comparably.
  constexpr double kResidualTolerance = 1e-10;
  std::vector<Override> overrides = compressor_pedestal();
  overrides.insert(overrides.end(), {{"bearings.turbine.pedestal_mass", "0.8"},
                                     {"bearings.turbine.pedestal_stiffness", "5e7"},
                                     {"bearings.turbine.pedestal_damping", "100"}});
  MachineSpec spec = reference(overrides);
  spec.speed.end = 60000 * kRpmToRadPerS;
  const auto model = make_runup_model(spec);
  ASSERT_GT(model->n_element_states(), 4);
  auto ws = model->make_workspace();
  const int ny = model->n_states();
  const Eigen::VectorXd y = Eigen::VectorXd::Random(ny) * 1e-5;
  const double t = 1.3, gamma = 1e-5;
  const Eigen::MatrixXd J = model->JacobianMatrix(t, y.data(), *ws);
  EXPECT_LT(testing::newton_solve_residual(*model, *ws, J, gamma), kResidualTolerance);
}

TEST(Jacobian, RespunJacobianSolvesAsAFreshOneWhereOnlyTheRotorDependsOnTheSpeed) {
  // The integrator's cheap refresh when only the speed has moved: the rotor's gyroscopic terms moved to the new spin,
  // the elements' blocks kept. With linear pedestal bearings (speed-independent blocks) the Newton solve must then
  // be that of a fresh Jacobian, and differ from that of the old one (the ramp's speed doubles).
  MachineSpec spec = reference(compressor_pedestal());
  spec.speed.end = 150000 * kRpmToRadPerS;
  const auto model = make_runup_model(spec);
  auto ws = model->make_workspace();
  const int ny = model->n_states();
  const Eigen::VectorXd y = Eigen::VectorXd::Random(ny) * 1e-5, b = Eigen::VectorXd::Random(ny);
  const double t0 = 1.0, t1 = 2.0, gamma = 1e-4;
  auto newton = [&] {
    Eigen::VectorXd x(ny);
    EXPECT_TRUE(model->FactorNewton(gamma, *ws));
    model->SolveNewton(gamma, b.data(), x.data(), *ws);
    return x;
  };
  model->Jacobian(t1, y.data(), *ws);
  const Eigen::VectorXd fresh = newton();
  model->Jacobian(t0, y.data(), *ws);
  const Eigen::VectorXd old = newton();
  model->RespinJacobian(t1, *ws);
  const Eigen::VectorXd respun = newton();
  const double scale = fresh.cwiseAbs().maxCoeff();
  EXPECT_LT((respun - fresh).cwiseAbs().maxCoeff(), 1e-10 * scale);
  EXPECT_GT((old - fresh).cwiseAbs().maxCoeff(), 1e-4 * scale);
}

// Forwards an element. With `jacobian` false it hides the element's analytic Jacobian, so the engine differentiates
// it numerically; with a `factor` it declares absolute tolerances of its states that depend on the state:
// factor(z_i) on each state's scaled tolerance.
class Forwarding final : public ForceElement {
 public:
  explicit Forwarding(std::unique_ptr<ForceElement> inner, bool jacobian, double (*factor)(double) = nullptr)
      : ForceElement(inner->name(), inner->dofs(), inner->n_states()),
        inner_(std::move(inner)),
        jacobian_(jacobian),
        factor_(factor) {}
  void initial_states(double* z) const override { inner_->initial_states(z); }
  double state_scale(int i) const override { return inner_->state_scale(i); }
  double tolerance_scale(int i) const override { return inner_->tolerance_scale(i); }
  bool has_jacobian() const override { return jacobian_ && inner_->has_jacobian(); }
  void add_jacobian(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                   double* J) const override {
    inner_->add_jacobian(s, q, v, z, ws, J);
  }
  bool has_state_dependent_tolerances() const override { return factor_ != nullptr; }
  void absolute_tolerance_factors(const double* z, double* f) const override {
    for (int i = 0; i < n_states(); ++i) f[i] = factor_(z[i]);
  }

 protected:
  void do_calc_and_add_forces(const SpinState& s, const double* q, const double* v, const double* z, ElementWorkspace& ws,
                          double* f, double* zdot) const override {
    inner_->calc_and_add_forces(s, q, v, z, ws, f, zdot);
  }

 private:
  std::unique_ptr<ForceElement> inner_;
  bool jacobian_;
  double (*factor_)(double);
};

// State-dependent tolerances (ForceElement::absolute_tolerance_factors) go into the integrator's error weights:
// factors of 1 give CVODE's own weights bit for bit, factors that depend on the state change the run.
TEST(Runup, StateDependentTolerancesEnterTheErrorWeights) {
  MachineSpec spec = reference(compressor_pedestal());
  spec.speed.end = 10000 * kRpmToRadPerS;
  spec.speed.duration = 0.02;
  spec.solver.atol_scaling = AtolScaling::Typical;
  auto build = [&](double (*factor)(double)) {
    Rotor rotor = build_rotor(spec);
    std::vector<std::unique_ptr<ForceElement>> elements;
    for (const LinearBearing& b : rotor.bearings) {
      const Pedestal p = b.name == "compressor" ? Pedestal{0.5, 2e7, 300} : Pedestal{};
      std::unique_ptr<ForceElement> e = std::make_unique<LinearBearingElement>(b, rotor.dof(b.node, kX), p, 9.81);
      if (e->n_states() > 0) e = std::make_unique<Forwarding>(std::move(e), true, factor);
      elements.push_back(std::move(e));
    }
    return std::make_unique<RunupModel>(spec, std::move(rotor), std::move(elements), 0.0);
  };
  const auto plain = build(nullptr);
  const auto ones = build([](double) { return 1.0; });
  // Tight where the pedestal has moved by more than 0.1 um: 1e-3 of the tolerance there.
  const auto tight = build([](double z) { return std::abs(z) > 1e-7 ? 1e-3 : 1.0; });
  RunupOptions o = options_for(spec);
  {
    const RunupResult a = simulate_runup(*plain, o), b = simulate_runup(*ones, o), c = simulate_runup(*tight, o);
    ASSERT_TRUE(a.complete && b.complete && c.complete) << a.message << b.message << c.message;
    EXPECT_EQ(a.stats.steps, b.stats.steps);
    EXPECT_EQ(a.columns, b.columns);
    EXPECT_GT(c.stats.steps, a.stats.steps);
  }
  // The explicit integrator takes them too. ARKODE forms its own weights with other round-off, and its steps here
  // are set by stability, so: the same run within round-off with factors of 1, another one with the tight factors.
  o.solver.integrator = Integrator::ArkodeErk;
  const RunupResult a = simulate_runup(*plain, o), b = simulate_runup(*ones, o), c = simulate_runup(*tight, o);
  ASSERT_TRUE(a.complete && b.complete && c.complete) << a.message << b.message << c.message;
  double same = 0.0, other = 0.0;
  for (std::size_t k = 1; k < a.columns.size(); ++k) {
    const double scale = max_abs(a.columns[k]) + 1e-300;
    for (std::size_t i = 0; i < a.columns[k].size(); ++i) {
      same = std::max(same, std::abs(b.columns[k][i] - a.columns[k][i]) / scale);
      other = std::max(other, std::abs(c.columns[k][i] - a.columns[k][i]) / scale);
    }
  }
  EXPECT_LT(same, 1e-9);
  EXPECT_GT(other, 1e3 * same);
}

TEST(Jacobian, NumericalElementJacobianMatchesTheAnalyticOne) {
  MachineSpec spec = reference({{"bearings.turbine.pedestal_mass", "0.5"},
                                {"bearings.turbine.pedestal_stiffness", "2e7"},
                                {"bearings.turbine.pedestal_damping", "300"}});
  auto build = [&](bool numeric) {
    Rotor rotor = build_rotor(spec);
    std::vector<std::unique_ptr<ForceElement>> elements;
    for (std::size_t i = 0; i < rotor.bearings.size(); ++i) {
      const LinearBearing& b = rotor.bearings[i];
      const Pedestal p = b.name == "turbine" ? Pedestal{0.5, 2e7, 300} : Pedestal{};
      std::unique_ptr<ForceElement> e = std::make_unique<LinearBearingElement>(b, rotor.dof(b.node, kX), p, 9.81);
      if (numeric) e = std::make_unique<Forwarding>(std::move(e), false);
      elements.push_back(std::move(e));
    }
    return std::make_unique<RunupModel>(spec, std::move(rotor), std::move(elements), 7500.0);
  };
  const auto analytic = build(false), numeric = build(true);
  auto wa = analytic->make_workspace(), wn = numeric->make_workspace();
  Eigen::VectorXd y = Eigen::VectorXd::Random(analytic->n_states()) * 1e-5;
  const Eigen::MatrixXd Ja = analytic->JacobianMatrix(0.7, y.data(), *wa);
  const Eigen::MatrixXd Jn = numeric->JacobianMatrix(0.7, y.data(), *wn);
  // Forward differences with step sqrt(eps) * typical size on a linear element: no truncation error, round-off
  // of order eps |f| / h, here below 1e-4 of each column's scale (Pinocchio/Ceres check Jacobians at ~sqrt(h)).
  constexpr double kFiniteDifferenceTolerance = 1e-4;
  for (int j = 0; j < Ja.cols(); ++j) {
    const double scale = Ja.col(j).cwiseAbs().maxCoeff();
    EXPECT_LT((Ja.col(j) - Jn.col(j)).cwiseAbs().maxCoeff(), kFiniteDifferenceTolerance * scale + 1e-12)
        << "column " << j;
  }
}

TEST(Statics, GravityIsCarriedByTheSupports) {
  // Static equilibrium: the pedestal supports carry the rotor's weight plus their own (force balance). The rotor
  // stands still without angular acceleration (which would add tangential unbalance forces U Omega').
  const MachineSpec spec = reference({{"speed.end", "0"},
                                      {"bearings.compressor.pedestal_mass", "0.5"},
                                      {"bearings.compressor.pedestal_stiffness", "2e7"},
                                      {"bearings.turbine.pedestal_mass", "0.7"},
                                      {"bearings.turbine.pedestal_stiffness", "3e7"}});
  const auto model = make_runup_model(spec);
  auto ws = model->make_workspace();
  std::vector<double> y(model->n_states()), out(model->channels().size());
  model->InitialState(0.0, true, y.data(), *ws);
  model->Probes(0.0, y.data(), *ws, out.data());
  double fy = 0.0;
  for (std::size_t c = 0; c < out.size(); ++c)
    if (model->channels()[c].name.find(".fy") != std::string::npos) fy += out[c];
  const double weight = (model->rotor().total_mass + 0.5 + 0.7) * spec.gravity;
  EXPECT_NEAR(fy / -weight, 1.0, 1e-9);  // the housing pulls up: the force on the housing points down
}

// A slow ramp through a speed window with no critical speed: the order-tracked 1x amplitude equals the
// frequency-domain steady-state response (issue acceptance: within 2 %).
TEST(Runup, SlowRampMatchesSteadyStateResponse) {
  constexpr double kSteadyTolerance = 0.02;
  MachineSpec spec = reference({{"bearings.compressor.c", "500"}, {"bearings.turbine.c", "500"}});
  spec.speed.kind = SpeedProfile::Kind::Table;
  spec.speed.times = {0.0, 0.3, 3.3};
  spec.speed.speeds = {0.0, 55000 * kRpmToRadPerS, 100000 * kRpmToRadPerS};
  spec.speed.end = spec.speed.speeds.back();
  spec.speed.duration = spec.speed.times.back();
  const auto model = make_runup_model(spec);
  const signal::OrderTrack track = order_track_of_run(*model, spec, "disk.compressor.x", 100, 40);
  ASSERT_FALSE(track.speeds.empty());
  const Rotor& rotor = model->rotor();
  int compared = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < track.speeds.size(); ++i) {
    const double rpm = track.speeds[i] * 60.0;
    if (rpm < 62000 || rpm > 97000) continue;  // after the start-up transient has decayed
    const SteadyResponse s = unbalance_response(rotor, track.speeds[i] * 2 * M_PI);
    const double expected = std::abs(s.q(rotor.dof(rotor.disks[0].name == "compressor" ? rotor.disks[0].node
                                                                                         : rotor.disks[1].node,
                                                    kX)));
    EXPECT_NEAR(track.amplitude[i] / expected, 1.0, kSteadyTolerance) << rpm << " rpm";
    worst = std::max(worst, std::abs(track.amplitude[i] / expected - 1.0));
    ++compared;
  }
  EXPECT_GT(compared, 30);
  std::cout << "[ validation ] slow ramp vs steady state: largest deviation " << 100 * worst << " % over " << compared
            << " points\n";
}

// Passing a critical speed at the paper's acceleration: the 1x peak comes later and lower than the steady-state
// peak (Lewis 1932, "Vibration during acceleration through a critical speed", Trans. ASME 54; Markert & Seidler
// 2001, Meccanica 36).
TEST(Runup, FastRampShiftsAndShrinksThePeak) {
  MachineSpec spec = reference();
  spec.speed.end = 60000 * kRpmToRadPerS;
  spec.speed.duration = 4.0 * 60000.0 / 150000.0;  // the paper's 37,500 rpm/s
  ASSERT_EQ(spec.output.sample_rate, 20000.0);
  const auto model = make_runup_model(spec);
  const signal::OrderTrack tr = order_track_of_run(*model, spec, "disk.turbine.x", 400, 4);
  ASSERT_FALSE(tr.speeds.empty());
  // The first forward critical (turbine-side mode) is near 30,700 rpm; look at 20,000 - 38,000 rpm.
  double run_peak = 0, run_speed = 0;
  for (std::size_t i = 0; i < tr.speeds.size(); ++i)
    if (tr.speeds[i] * 60 > 20000 && tr.speeds[i] * 60 < 38000 && tr.amplitude[i] > run_peak) {
      run_peak = tr.amplitude[i];
      run_speed = tr.speeds[i] * 60;
    }
  const Rotor& rotor = model->rotor();
  const int node = rotor.disks[0].name == "turbine" ? rotor.disks[0].node : rotor.disks[1].node;
  double steady_peak = 0, steady_speed = 0;
  for (double rpm = 20000; rpm < 38000; rpm += 10) {
    const double a = std::abs(unbalance_response(rotor, rpm * kRpmToRadPerS).q(rotor.dof(node, kX)));
    if (a > steady_peak) {
      steady_peak = a;
      steady_speed = rpm;
    }
  }
  EXPECT_GT(run_speed, steady_speed);
  EXPECT_LT(run_peak, steady_peak);
  std::cout << "[ validation ] steady peak " << steady_peak * 1e6 << " um at " << steady_speed << " rpm; run-up peak "
            << run_peak * 1e6 << " um at " << run_speed << " rpm\n";
}

TEST(Runup, TighterToleranceChangesMaximaByLessThanOnePercent) {
  constexpr double kMaximaChange = 0.01;
  MachineSpec spec = reference();
  spec.speed.end = 60000 * kRpmToRadPerS;
  spec.speed.duration = 1.6;
  const auto model = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  const RunupResult a = simulate_runup(*model, o);
  o.solver.rtol /= 10;
  o.solver.atol /= 10;
  const RunupResult b = simulate_runup(*model, o);
  ASSERT_TRUE(a.complete && b.complete);
  for (const char* name : {"disk.compressor.x", "disk.turbine.y", "bearing.compressor.fx"}) {
    const double ratio = max_abs(a.columns[channel(a, name)]) / max_abs(b.columns[channel(b, name)]);
    EXPECT_NEAR(ratio, 1.0, kMaximaChange) << name;
    std::cout << "[ validation ] rtol 1e-6 vs 1e-7, max |" << name << "| changes by " << 100 * (ratio - 1) << " %\n";
  }
}

TEST(Runup, NewtonToleranceReachesTheIntegratorAndLeavesTheMaxima) {
  // CVODE's Newton test (nlscoef): a tighter one takes more right-hand sides per step; the answer stays within
  // the error test's own tolerance.
  MachineSpec spec = reference(compressor_pedestal());
  spec.speed.end = 30000 * kRpmToRadPerS;
  spec.speed.duration = 0.4;
  const auto model = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  o.solver.newton_tolerance = 1e-3;
  const RunupResult tight = simulate_runup(*model, o);
  o.solver.newton_tolerance = 0.5;
  const RunupResult loose = simulate_runup(*model, o);
  ASSERT_TRUE(tight.complete && loose.complete) << tight.message << loose.message;
  const double per_step_tight = double(tight.stats.rhs_calls) / double(tight.stats.steps);
  const double per_step_loose = double(loose.stats.rhs_calls) / double(loose.stats.steps);
  EXPECT_GT(per_step_tight, 1.1 * per_step_loose);
  for (const char* name : {"disk.compressor.x", "disk.turbine.y", "bearing.compressor.fx"}) {
    const double ratio = max_abs(loose.columns[channel(loose, name)]) / max_abs(tight.columns[channel(tight, name)]);
    EXPECT_NEAR(ratio, 1.0, 0.01) << name;
  }
}

TEST(Runup, TypicalToleranceScalingResolvesEveryStateToTheSameFraction) {
  // atol_scaling = "typical": displacements get atol, velocities atol x (1 mm/s / 1 um), element states atol x their
  // tolerance scale / 1 um (the pedestals' typical magnitudes); "uniform" gives atol for every state.
  MachineSpec spec = reference({{"bearings.compressor.pedestal_mass", "0.5"},
                                {"bearings.compressor.pedestal_stiffness", "2e7"}});
  const auto model = make_runup_model(spec);
  const int n = model->n_dof(), ny = model->n_states();
  const Eigen::VectorXd u = model->AbsoluteTolerances(1e-10, false);
  EXPECT_EQ(u.minCoeff(), 1e-10);
  EXPECT_EQ(u.maxCoeff(), 1e-10);
  const Eigen::VectorXd a = model->AbsoluteTolerances(1e-10, true);
  ASSERT_EQ(a.size(), ny);
  for (int i = 0; i < n; ++i) {
    EXPECT_DOUBLE_EQ(a(i), 1e-10);
    EXPECT_DOUBLE_EQ(a(n + i), 1e-7);
  }
  for (std::size_t k = 0; k < model->elements().size(); ++k)
    for (int i = 0; i < model->elements()[k]->n_states(); ++i)
      EXPECT_DOUBLE_EQ(a(model->state_offset(static_cast<int>(k)) + i),
                       1e-10 * model->elements()[k]->tolerance_scale(i) / 1e-6);
  // A run with the scaled tolerances gives the same maxima as the default within the accuracy both ask for.
  spec.speed.end = 30000 * kRpmToRadPerS;
  spec.speed.duration = 0.8;
  const auto m2 = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  const RunupResult r0 = simulate_runup(*m2, o);
  o.solver.atol_scaling = AtolScaling::Typical;
  o.solver.atol = 1e-10;
  const RunupResult r1 = simulate_runup(*m2, o);
  ASSERT_TRUE(r0.complete && r1.complete);
  constexpr double kMaximaAgreement = 0.01;
  for (const char* name : {"disk.compressor.x", "bearing.compressor.fx"}) {
    const double ratio = max_abs(r1.columns[channel(r1, name)]) / max_abs(r0.columns[channel(r0, name)]);
    EXPECT_NEAR(ratio, 1.0, kMaximaAgreement) << name;
  }
  o.solver.atol_scaling = static_cast<AtolScaling>(7);
  EXPECT_THROW(simulate_runup(*m2, o), std::invalid_argument);
}

TEST(Runup, EnergyBalanceCloses) {
  // Work of the unbalance and of the spin acceleration on the gyroscopic term = change of kinetic + potential
  // energy + energy dissipated in the bearings (with a damped pedestal as an internal-state element).
  MachineSpec spec = reference({{"bearings.turbine.pedestal_mass", "0.5"},
                                {"bearings.turbine.pedestal_stiffness", "2e7"},
                                {"bearings.turbine.pedestal_damping", "200"}});
  spec.speed.end = 60000 * kRpmToRadPerS;
  spec.speed.duration = 1.6;
  const auto model = make_runup_model(spec);
  const RunupResult r = simulate_runup(*model, options_for(spec));
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_GT(r.work_in, 0.0);
  const double error = r.energy_final - r.energy_initial - r.work_in + r.dissipated;
  EXPECT_LT(std::abs(error), 1e-3 * r.work_in);
  std::cout << "[ validation ] energy balance error " << error << " J of " << r.work_in << " J work in\n";
}

TEST(Runup, ExplicitAndImplicitIntegratorsAgree) {
  MachineSpec spec = reference();
  spec.speed.end = 40000 * kRpmToRadPerS;
  spec.speed.duration = 0.4;
  const auto model = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  o.solver.integrator = Integrator::CvodeBdf;
  const RunupResult bdf = simulate_runup(*model, o);
  o.solver.integrator = Integrator::ArkodeErk;
  const RunupResult erk = simulate_runup(*model, o);
  ASSERT_TRUE(bdf.complete && erk.complete) << bdf.message << erk.message;
  const int c = channel(bdf, "disk.compressor.x");
  EXPECT_NEAR(max_abs(bdf.columns[c]) / max_abs(erk.columns[c]), 1.0, 0.01);
}

TEST(Runup, IntegratorFailureKeepsTheSamplesAndSaysWhenAndWhy) {
  MachineSpec spec = reference();
  const auto model = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  o.solver.max_steps = 200;  // the integrator gives up after 200 steps between two output samples
  o.sample_rate = 200;
  for (const Integrator integrator : {Integrator::CvodeBdf, Integrator::ArkodeErk}) {
    o.solver.integrator = integrator;
    const RunupResult r = simulate_runup(*model, o);
    EXPECT_FALSE(r.complete);
    EXPECT_THAT(r.message, HasSubstr("stopped at t = "));
    EXPECT_THAT(r.message, HasSubstr("rpm"));
    EXPECT_THAT(r.message, HasSubstr("TOO_MUCH_WORK"));
    EXPECT_GT(r.time.size(), 1u);
    EXPECT_EQ(r.columns[0].size(), r.time.size());
    EXPECT_LT(r.t_reached, spec.speed.duration);
  }
}

TEST(Runup, CancellationStopsEarly) {
  const MachineSpec spec = reference();
  const auto model = make_runup_model(spec);
  RunupOptions o = options_for(spec);
  std::atomic<bool> cancel{true};
  o.cancel = &cancel;
  const RunupResult r = simulate_runup(*model, o);
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.message, HasSubstr("interrupted"));
  // The right-hand side sees the flag: the run stops inside its first output interval, with the initial sample.
  EXPECT_EQ(r.time.size(), 1u);
  EXPECT_LT(r.t_reached, 1.0 / spec.output.sample_rate);
}

}  // namespace
}  // namespace turbodyn
