// Cost of one force evaluation of one ball bearing (reference bearing, 8 balls, 82 states) at a realistic state:
// preload 40 N, 100,000 rpm, radial load about 20 N, and of the finite-difference Jacobian the run-up engine
// would take of it: (2 * 4 + n_states + 1) evaluations.
// The balls carry their no-slip speeds at 100,000 rpm (steady_states), so every contact has slip, friction and spin.
// Run: build/bench/ball_bearing_benchmark --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "model/elements/ball/ball_bearing.h"

namespace {

using namespace turbodyn;

struct Setup {
  BallBearingSpec spec;
  BallBearingElement element{"bench", spec, 0, 9.81};
  std::unique_ptr<ElementWorkspace> ws = element.make_workspace();
  std::vector<double> z = std::vector<double>(element.n_states());
  std::vector<double> zdot = std::vector<double>(element.n_states());
  // Balls at the static preload positions (not re-equilibrated), so the shaft sees the stiffer inner contacts
  // only: 0.2 um gives about 20 N (the counter shaft_force_x).
  double q[4] = {0.2e-6, 0.0, 0.0, 0.0};
  double v[4] = {0.0, 0.0, 0.0, 0.0};
  SpinState s{0.0, 100000 * 2 * M_PI / 60, 0.0, 0.0};
  Setup() {
    element.initial_states(z.data());
    element.steady_states(s.speed, z.data());
  }
};

void Forces(benchmark::State& state) {
  Setup b;
  double f[4] = {0, 0, 0, 0};
  for (auto _ : state) {
    b.element.calc_and_add_forces(b.s, b.q, b.v, b.z.data(), *b.ws, f, b.zdot.data());
    benchmark::DoNotOptimize(f);
    benchmark::ClobberMemory();
  }
  state.counters["states"] = b.element.n_states();
  state.counters["shaft_force_x"] = f[0] / static_cast<double>(state.iterations());  // f accumulates
}

// Forward differences over [q; v; z] as model/engine/runup.cpp does for elements without an analytic Jacobian.
void FiniteDifferenceJacobian(benchmark::State& state) {
  Setup b;
  const int d = 4, m = b.element.n_states();
  std::vector<double> in(2 * d + m), out0(d + m), out1(d + m), J((d + m) * (2 * d + m));
  std::copy(b.q, b.q + d, in.begin());
  std::copy(b.v, b.v + d, in.begin() + d);
  std::copy(b.z.begin(), b.z.end(), in.begin() + 2 * d);
  const auto eval = [&](std::vector<double>& out) {
    std::fill(out.begin(), out.begin() + d, 0.0);
    b.element.calc_and_add_forces(b.s, in.data(), in.data() + d, in.data() + 2 * d, *b.ws, out.data(), out.data() + d);
  };
  const double rel = b.element.fd_relative_step();
  for (auto _ : state) {
    eval(out0);
    for (int j = 0; j < 2 * d + m; ++j) {
      const double saved = in[j];
      const double typical = j < d ? 1e-6 : j < 2 * d ? 1e-3 : b.element.state_scale(j - 2 * d);
      const double h = rel * std::max(std::abs(saved), typical);
      in[j] = saved + h;
      eval(out1);
      in[j] = saved;
      for (int i = 0; i < d + m; ++i) J[j * (d + m) + i] = (out1[i] - out0[i]) / h;
    }
    benchmark::DoNotOptimize(J.data());
    benchmark::ClobberMemory();
  }
  state.counters["evaluations"] = 2 * d + m + 1;
}

BENCHMARK(Forces);
BENCHMARK(FiniteDifferenceJacobian);

}  // namespace

BENCHMARK_MAIN();
