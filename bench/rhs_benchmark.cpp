// Cost of one right-hand-side evaluation and one Jacobian evaluation of the run-up equations.
#include <benchmark/benchmark.h>

#include <vector>

#include "model/io/model_file.h"
#include "model/engine/runup.h"

namespace {

using namespace turbodyn;

std::unique_ptr<RunupModel> reference(const std::vector<Override>& overrides) {
  return make_runup_model(load_model(TURBODYN_SOURCE_DIR "/examples/reference_linear.toml", overrides));
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

BENCHMARK_CAPTURE(Rhs, linear_reduced, std::vector<Override>{});
BENCHMARK_CAPTURE(Rhs, linear_unreduced, std::vector<Override>{{"solver.reduction_cutoff", "0"}});
BENCHMARK_CAPTURE(Rhs, linear_pedestals_reduced,
                  std::vector<Override>{{"bearings.compressor.pedestal_mass", "0.5"},
                                        {"bearings.compressor.pedestal_stiffness", "2e7"},
                                        {"bearings.turbine.pedestal_mass", "0.5"},
                                        {"bearings.turbine.pedestal_stiffness", "2e7"}});
BENCHMARK_CAPTURE(Jacobian, linear_reduced, std::vector<Override>{});
BENCHMARK_CAPTURE(Jacobian, linear_unreduced, std::vector<Override>{{"solver.reduction_cutoff", "0"}});

}  // namespace

BENCHMARK_MAIN();
