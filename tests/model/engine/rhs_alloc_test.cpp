// The right-hand side of the equations of motion allocates nothing (STYLE.md; Drake's LimitMalloc idea); the
// counting operator new comes from tests/support/alloc_counter.cpp.

#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "model/engine/runup.h"
#include "tests/support/alloc_counter.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

TEST(RhsAllocation, NoHeapAllocationInTheRightHandSide) {
  struct Case {
    std::string file, label;
    std::vector<Override> overrides;
  };
  // Linear bearings; a pedestal (element states); ball bearings (element states factored ball by ball); floating
  // rings (two Reynolds films per bearing).
  const std::vector<Case> cases = {
      {"reference_linear.toml", "without pedestal", {}},
      {"reference_linear.toml", "with pedestal",
       {{"bearings.turbine.pedestal_mass", "0.5"}, {"bearings.turbine.pedestal_stiffness", "2e7"}}},
      {"reference_ball.toml", "ball bearings", {}},
      {"reference_floating_ring.toml", "floating rings", {}},
      {"reference_floating_ring.toml", "thermal floating rings",
       {{"bearings.compressor.thermal", "bulk"}, {"bearings.turbine.thermal", "bulk"}}}};
  for (const Case& c : cases) {
    const MachineSpec spec = load_model(testing::source_dir() + "/examples/" + c.file, c.overrides);
    const auto model = make_runup_model(spec);
    auto ws = model->make_workspace();
    // The elements' initial states (thermal films at the supply temperature, all else 0), every state moved by 1e-6.
    std::vector<double> y(model->n_states()), ydot(model->n_states());
    model->InitialState(0.5, false, y.data(), *ws);
    for (double& yi : y) yi += 1e-6;
    model->Rhs(0.5, y.data(), ydot.data(), *ws);  // warm-up
    const long before = testing::allocation_count();
    for (int i = 0; i < 100; ++i) model->Rhs(0.5 + 1e-4 * i, y.data(), ydot.data(), *ws);
    EXPECT_EQ(testing::allocation_count() - before, 0) << c.label;
    // The Newton factorisation and solve of the BDF corrector, called at every step, allocate nothing either; nor
    // does the floating rings' own Jacobian (perturbed film solves and back-substitutions).
    model->Jacobian(0.5, y.data(), *ws);
    if (c.label.find("floating rings") != std::string::npos) {
      const long before_jacobian = testing::allocation_count();
      for (int i = 0; i < 3; ++i) model->Jacobian(0.5 + 1e-4 * i, y.data(), *ws);
      EXPECT_EQ(testing::allocation_count() - before_jacobian, 0) << "Jacobian, " << c.label;
    }
    std::vector<double> x(model->n_states());
    model->FactorNewton(1e-5, *ws);
    model->SolveNewton(1e-5, ydot.data(), x.data(), *ws);  // warm-up
    const long before_newton = testing::allocation_count();
    for (int i = 0; i < 10; ++i) {
      model->FactorNewton(1e-5 * (1 + i), *ws);
      model->SolveNewton(1e-5 * (1 + i), ydot.data(), x.data(), *ws);
    }
    EXPECT_EQ(testing::allocation_count() - before_newton, 0) << "Newton solve, " << c.label;
  }
  // With the bearings side by side on two threads (ElementTeam), the right-hand side and the Jacobian allocate
  // nothing either, and give the same numbers as one thread.
  {
    const MachineSpec spec = load_model(testing::source_dir() + "/examples/reference_floating_ring.toml");
    const auto model = make_runup_model(spec);
    auto ws1 = model->make_workspace(1), ws2 = model->make_workspace(2);
    std::vector<double> y(model->n_states(), 1e-6), ydot1(model->n_states()), ydot2(model->n_states());
    model->Rhs(0.5, y.data(), ydot2.data(), *ws2);  // warm-up
    model->Jacobian(0.5, y.data(), *ws2);
    const long before_team = testing::allocation_count();
    for (int i = 0; i < 20; ++i) model->Rhs(0.5 + 1e-4 * i, y.data(), ydot2.data(), *ws2);
    model->Jacobian(0.5, y.data(), *ws2);
    EXPECT_EQ(testing::allocation_count() - before_team, 0) << "two threads";
    model->Rhs(0.5, y.data(), ydot1.data(), *ws1);
    model->Rhs(0.5, y.data(), ydot2.data(), *ws2);
    EXPECT_EQ(ydot1, ydot2);
    EXPECT_EQ(model->JacobianMatrix(0.5, y.data(), *ws1), model->JacobianMatrix(0.5, y.data(), *ws2));
  }
  // The counter works: a vector allocates.
  const long before = testing::allocation_count();
  std::vector<double> v(10);
  EXPECT_GT(testing::allocation_count() - before, 0);
}

}  // namespace
}  // namespace turbodyn
