// Cost of one Reynolds film evaluation (model/films/reynolds.h) on the 60 x 12 grid at eccentricity ratio 0.6, warm-started
// in a loop whose eccentricity vector turns slowly (0.25 degree per call, about one integrator step of a 500 Hz
// whirl at 7e5 steps/s), against a baseline that assembles the same full-film linear system and solves it with
// Eigen::SparseLU (analyse + factorise + solve on every call). docs/reynolds.md lists the measured numbers.
//
//   build/bench/reynolds_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Cases (the film is the reference turbocharger's inner film: journal 10 mm, width 7 mm, clearance 15 um,
// 10.8 mPa s, 100,000 rpm):
//   plain    no holes, no tilt (mid-width symmetric: half the axial unknowns are solved for)
//   squeeze  plain, plus the velocity of a forward whirl at 0.3 x the journal speed and a radial velocity
//   holes    four 2-mm coupling holes at mid-width at 0/90/180/270 deg at 2 bar (still symmetric)
//   tilt     holes plus a journal tilt of 0.3 c over the width (no symmetry: all 720 unknowns)
// The mass-conserving model needs an oil supply (docs/reynolds.md), so it runs only in the cases with holes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include <Eigen/SparseLU>

#include "model/films/reynolds.h"
#include "model/spec/constants.h"

namespace {

using namespace turbodyn::reynolds;
using turbodyn::kPi;

constexpr double kEta = 0.0108, kR = 0.005, kL = 0.007, kC = 15e-6;
constexpr double kOmega = 100000.0 * 2.0 * kPi / 60.0;
constexpr double kStep = 2.0 * kPi / 1440.0;  // eccentricity angle advanced per call

enum Case { kPlain = 0, kSqueeze = 1, kHoles = 2, kTilt = 3 };

FilmGeometry geometry(int c) {
  FilmGeometry g;
  g.radius = kR;
  g.length = kL;
  g.clearance = kC;
  g.n_circ = 60;
  g.n_axial = 12;
  if (c >= kHoles)
    for (int k = 0; k < 4; ++k) g.holes.push_back(Hole{k * kPi / 2.0, 0.0, 0.002, 2e5});
  return g;
}

FilmState state(int c, double angle) {
  FilmState s;
  const double e = 0.6 * kC;
  s.ex = e * std::cos(angle);
  s.ey = e * std::sin(angle);
  s.omega_inner = kOmega;
  if (c == kSqueeze) {
    const double whirl = 0.3 * kOmega, vr = 0.02 * kC * kOmega;
    s.vx = -e * whirl * std::sin(angle) + vr * std::cos(angle);
    s.vy = e * whirl * std::cos(angle) + vr * std::sin(angle);
  }
  if (c == kTilt) {
    s.sx = 0.3 * kC / kL * std::cos(angle + 1.0);
    s.sy = 0.3 * kC / kL * std::sin(angle + 1.0);
    s.ex *= 0.8;  // keep the film open at the ends
    s.ey *= 0.8;
  }
  return s;
}

// The film solver of benchmark case st.range(0) with the cavitation model st.range(1).
FilmSolver solver_of(const benchmark::State& st) {
  SolverOptions o;
  o.cavitation = static_cast<Cavitation>(st.range(1));
  return FilmSolver(geometry(static_cast<int>(st.range(0))), kEta, o);
}

void Film(benchmark::State& st) {
  const int c = static_cast<int>(st.range(0));
  FilmSolver solver = solver_of(st);
  FilmResult r;
  double angle = 0.0;
  for (int k = 0; k < 200; ++k) solver.solve(state(c, angle += kStep), r);  // warm up, as in a running integration
  long iterations = 0, solves = 0, calls = 0;
  for (auto _ : st) {
    if (!solver.solve(state(c, angle += kStep), r)) st.SkipWithError(solver.last_error().c_str());
    benchmark::DoNotOptimize(r.fx);
    iterations += r.iterations;
    solves += r.linear_solves;
    ++calls;
  }
  st.counters["sweeps/call"] = static_cast<double>(iterations) / calls;
  st.counters["solves/call"] = static_cast<double>(solves) / calls;
  st.counters["symmetric"] = r.symmetric ? 1 : 0;
}

// The same full-film system (all 720 nodes, Dirichlet rows as identity) assembled and solved by SparseLU per call.
void SparseLuBaseline(benchmark::State& st) {
  const int c = static_cast<int>(st.range(0));
  SolverOptions o;
  o.cavitation = Cavitation::None;
  const FilmSolver solver(geometry(c), kEta, o);
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b, x;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  double angle = 0.0;
  for (auto _ : st) {
    solver.assemble_full_film_system(state(c, angle += kStep), A, b);
    lu.analyzePattern(A);
    lu.factorize(A);
    x = lu.solve(b);
    benchmark::DoNotOptimize(x.data());
  }
}

// Cold start (no warm-start state) for comparison.
void FilmCold(benchmark::State& st) {
  const int c = static_cast<int>(st.range(0));
  FilmSolver solver = solver_of(st);
  FilmResult r;
  double angle = 0.0;
  for (auto _ : st) {
    solver.reset_warm_start();
    if (!solver.solve(state(c, angle += kStep), r)) st.SkipWithError(solver.last_error().c_str());
    benchmark::DoNotOptimize(r.fx);
  }
}

void Args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"case", "cavitation"});
  for (int c : {kPlain, kSqueeze, kHoles, kTilt})
    for (int m = 0; m < 3; ++m)
      if (m != static_cast<int>(Cavitation::MassConserving) || c >= kHoles) b->Args({c, m});
}

BENCHMARK(Film)->Apply(Args)->Unit(benchmark::kMicrosecond);
BENCHMARK(FilmCold)->Apply(Args)->Unit(benchmark::kMicrosecond);
BENCHMARK(SparseLuBaseline)->ArgName("case")->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
