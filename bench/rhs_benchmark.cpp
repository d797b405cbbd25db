// Cost of one right-hand-side evaluation and one Jacobian evaluation of the run-up equations, and of the BDF
// corrector's Newton matrix with the ball bearings: its factorisation (at every new step size) and a solve (every
// Newton iteration).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "model/io/model_file.h"
#include "model/engine/runup.h"

namespace {

using namespace turbodyn;

std::unique_ptr<RunupModel> reference(const std::vector<Override>& overrides,
                                      const char* file = "reference_linear.toml") {
  return make_runup_model(load_model(std::string(TURBODYN_SOURCE_DIR "/examples/") + file, overrides));
}

void Rhs(benchmark::State& state, std::vector<Override> overrides) {
  const auto model = reference(overrides);
  auto ws = model->make_workspace();
  std::vector<double> y(model->n_states(), 1e-6), ydot(model->n_states());
  double t = 1.0;
  for (auto _ : state) {
    model->Rhs(t, y.data(), ydot.data(), *ws);
    benchmark::DoNotOptimize(ydot.data());
    t += 1e-7;
  }
  state.counters["states"] = model->n_states();
}

void Jacobian(benchmark::State& state, std::vector<Override> overrides) {
  const auto model = reference(overrides);
  auto ws = model->make_workspace();
  std::vector<double> y(model->n_states(), 1e-6);
  for (auto _ : state) {
    model->Jacobian(1.0, y.data(), *ws);
    benchmark::ClobberMemory();
  }
}

// The Newton matrix of `file` at its elements' initial states at 100,000 rpm (t = 2.667 s of the ramp: the balls at
// their no-slip speeds), with the Jacobian of that state.
void Newton(benchmark::State& state, const char* file, bool factor) {
  const auto model = reference({}, file);
  auto ws = model->make_workspace();
  const double t = 2.667;
  std::vector<double> y(model->n_states()), x(model->n_states()), b(model->n_states(), 1e-6);
  model->InitialState(t, false, y.data(), *ws);
  model->Jacobian(t, y.data(), *ws);
  double gamma = 1e-6;
  model->FactorNewton(gamma, *ws);
  for (auto _ : state) {
    if (factor) {
      gamma *= 1.0000001;
      benchmark::DoNotOptimize(model->FactorNewton(gamma, *ws));
    } else {
      model->SolveNewton(gamma, b.data(), x.data(), *ws);
      benchmark::DoNotOptimize(x.data());
    }
  }
  state.counters["states"] = model->n_states();
}

BENCHMARK_CAPTURE(Rhs, linear_reduced, std::vector<Override>{});
BENCHMARK_CAPTURE(Rhs, linear_unreduced, std::vector<Override>{{"solver.reduction_cutoff", "0"}});
BENCHMARK_CAPTURE(Rhs, linear_pedestals_reduced,
                  std::vector<Override>{{"bearings.compressor.pedestal_mass", "0.5"},
                                        {"bearings.compressor.pedestal_stiffness", "2e7"},
                                        {"bearings.turbine.pedestal_mass", "0.5"},
                                        {"bearings.turbine.pedestal_stiffness", "2e7"}});
BENCHMARK_CAPTURE(Jacobian, linear_reduced, std::vector<Override>{});
BENCHMARK_CAPTURE(Jacobian, linear_unreduced, std::vector<Override>{{"solver.reduction_cutoff", "0"}});
BENCHMARK_CAPTURE(Newton, factor_ball, "reference_ball.toml", true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Newton, solve_ball, "reference_ball.toml", false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Newton, factor_ball_sfd, "reference_ball_sfd.toml", true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Newton, solve_ball_sfd, "reference_ball_sfd.toml", false)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
